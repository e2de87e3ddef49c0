// Copyright 2026 The DCS Authors.
//
// The Eigen NatureCNN on hand-computed cases (its agreement with the learner's torch network is
// tested in tests/learner/actor_critic_test.cc), and the weights it refuses.

#include "actor/image_encoder.h"

#include <cstdint>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::actor {
namespace {

using ::testing::HasSubstr;

// A 3 x 3 image of two channels; one 2 x 2 convolution of stride 1 to two channels; a linear
// layer on its 2 x 2 x 2 output.
ImageEncoderWeights TinyEncoder() {
  ImageEncoderWeights weights{.height = 3, .width = 3, .channels = 2};
  ConvLayer conv{.in_channels = 2, .out_channels = 2, .kernel = 2, .stride = 1};
  // [out][in][ky][kx]: output 0 sums channel 0's field; output 1 takes channel 1's top left
  // minus its bottom right.
  conv.weight = {1, 1, 1, 1, /**/ 0, 0, 0, 0,  //
                 0, 0, 0, 0, /**/ 1, 0, 0, -1};
  conv.bias = {0, 0.5f};
  weights.convs.push_back(conv);
  // On the output flattened channel first: [channel][y][x]. Output 0 is channel 0 at (0, 0);
  // output 1 is channel 1 at (1, 0), negated.
  weights.linear = {.inputs = 8, .outputs = 2, .activation = Activation::kRelu};
  weights.linear.weight.assign(16, 0);
  weights.linear.weight[0 * 8 + 0 * 4 + 0] = 1;
  weights.linear.weight[1 * 8 + 1 * 4 + 2] = -1;
  weights.linear.bias = {0, 1};
  return weights;
}

TEST(ImageEncoderTest, ComputesConvolutionsAndTheLinearLayerByHand) {
  absl::StatusOr<ImageEncoder> encoder = ImageEncoder::Create(TinyEncoder());
  ASSERT_TRUE(encoder.ok()) << encoder.status();
  EXPECT_EQ(encoder->image_size(), 18);
  EXPECT_EQ(encoder->feature_size(), 2);
  // Channel last: pixel (y, x) is bytes [2 (3 y + x), 2 (3 y + x) + 1]. Channel 0 holds
  // 51 (3 y + x), channel 1 holds 255 at (1, 0) and 0 elsewhere.
  std::vector<uint8_t> image(18, 0);
  for (int p = 0; p < 9; ++p) image[2 * p] = static_cast<uint8_t>(51 * p);
  image[2 * 3 + 1] = 255;
  std::vector<float> features(2);
  encoder->Encode(image, features);
  // Channel 0 at (0, 0): pixels 0, 1, 3, 4 of channel 0 = (0 + 51 + 153 + 204) / 255 = 1.6.
  EXPECT_NEAR(features[0], 1.6f, 1e-6);
  // Channel 1 at (1, 0): relu(1 (top left, pixel 3) - 0 (pixel 7) + 0.5) = 1.5; then
  // relu(-1.5 + 1) = 0.
  EXPECT_EQ(features[1], 0.0f);
  image[2 * 3 + 1] = 51;  // 0.2: relu(0.2 + 0.5) = 0.7, then relu(-0.7 + 1) = 0.3
  encoder->Encode(image, features);
  EXPECT_NEAR(features[1], 0.3f, 1e-6);
}

TEST(ImageEncoderTest, RefusesLayersThatDoNotFit) {
  ImageEncoderWeights channels = TinyEncoder();
  channels.convs[0].in_channels = 3;
  EXPECT_THAT(ImageEncoder::Create(channels).status().message(),
              HasSubstr("convolution 0 does not fit"));

  ImageEncoderWeights kernel = TinyEncoder();
  kernel.convs[0].kernel = 4;  // larger than the image
  EXPECT_EQ(ImageEncoder::Create(kernel).status().code(), absl::StatusCode::kInvalidArgument);

  ImageEncoderWeights linear = TinyEncoder();
  linear.linear.inputs = 9;
  EXPECT_THAT(ImageEncoder::Create(linear).status().message(),
              HasSubstr("the encoder's linear layer does not fit"));

  ImageEncoderWeights tanh = TinyEncoder();
  tanh.linear.activation = Activation::kTanh;
  EXPECT_EQ(ImageEncoder::Create(tanh).status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::actor
