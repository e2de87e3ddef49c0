// Copyright 2026 The DCS Authors.
#include "learner/actor_critic.h"

#include <torch/torch.h>

#include <cmath>
#include <vector>

#include "actor/policy_network.h"
#include "common/random.h"
#include "env/car_racing.h"
#include "gtest/gtest.h"
#include "run/run_plan.h"
#include "tests/learner/policy_specs.h"

namespace dcs::learner {
namespace {

// The actor's Eigen network computes the same function as the learner's torch network.
void ExpectEigenMatchesTorch(const run::PolicySpec& spec, int samples,
                             const run::PpoConfig& config = run::PpoConfig{}) {
  torch::manual_seed(7);
  ActorCritic network(spec, config);
  absl::StatusOr<actor::PolicyNetwork> policy =
      actor::PolicyNetwork::Create(network->ExportActor());
  ASSERT_TRUE(policy.ok()) << policy.status();
  ASSERT_EQ(policy->input_size(), spec.flat_input_size());
  const int image_size = static_cast<int>(spec.image_size());
  ASSERT_EQ(policy->image_size(), image_size);
  Random random(3);
  const int head = spec.head_size();
  for (int sample = 0; sample < samples; ++sample) {
    std::vector<float> input(spec.flat_input_size());
    for (float& x : input) x = static_cast<float>(random.Uniform(-3, 3));
    std::vector<uint8_t> image(image_size);
    for (uint8_t& byte : image) byte = static_cast<uint8_t>(random.Integers(0, 256));
    std::vector<float> eigen(head);
    policy->Forward(1, input, image, eigen);
    torch::NoGradGuard no_grad;
    const ObservationBatch batch{
        .flat = torch::from_blob(input.data(), {1, spec.flat_input_size()}), .images = image};
    ActorCriticImpl::Pass pass;
    network->Forward(batch, /*for_backward=*/false, pass);
    for (int i = 0; i < head; ++i) {
      EXPECT_NEAR(eigen[i], pass.head(i, 0), 1e-5) << "sample " << sample;
    }
  }
}

TEST(ActorCriticTest, EigenInferenceMatchesTorchForCategoricalPolicies) {
  ExpectEigenMatchesTorch(CartPoleSpec(), 200);
}

TEST(ActorCriticTest, EigenInferenceMatchesTorchForGaussianPolicies) {
  ExpectEigenMatchesTorch(WalkerSpec(), 200);
}

TEST(ActorCriticTest, EigenInferenceMatchesTorchForImagePolicies) {
  // CarRacing's: a 96 x 96 RGB image and one context value, three continuous actions.
  ExpectEigenMatchesTorch(run::PolicySpecFor<env::CarRacing>(1), 20);
}

TEST(ActorCriticTest, EigenInferenceMatchesTorchForImagePoliciesWithAContextBranch) {
  ExpectEigenMatchesTorch(run::PolicySpecFor<env::CarRacing>(1), 20,
                          run::PpoConfig{.context_layers = {64, 16}});
}

TEST(ActorCriticTest, InitialisesWithSb3Gains) {
  // Orthogonal rows scaled by the gain: W W^T = gain^2 I for a wide layer (64 x 5 is tall, so
  // use W^T W = gain^2 I on the 64 x 64 hidden layer), 0.01 for the action head, zero biases.
  torch::manual_seed(1);
  ActorCritic network(CartPoleSpec(), run::PpoConfig{});
  const actor::PolicyWeights weights = network->ExportActor();
  ASSERT_EQ(weights.layers.size(), 3u);  // 5 -> 64 -> 64 -> 2
  const actor::DenseLayer& hidden = weights.layers[1];
  ASSERT_EQ(hidden.inputs, 64);
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      double dot = 0;
      for (int k = 0; k < 64; ++k) dot += hidden.weight[a * 64 + k] * hidden.weight[b * 64 + k];
      EXPECT_NEAR(dot, a == b ? 2.0 : 0.0, 1e-4);
    }
  }
  const actor::DenseLayer& head = weights.layers[2];
  double row = 0;
  for (int k = 0; k < 64; ++k) row += head.weight[k] * head.weight[k];
  EXPECT_NEAR(std::sqrt(row), 0.01, 1e-5);
  for (const actor::DenseLayer& layer : weights.layers) {
    for (float b : layer.bias) EXPECT_EQ(b, 0.0f);
  }
}

TEST(ActorCriticTest, ImagePoliciesRunNatureCnnOnTheImageAndAppendTheContext) {
  torch::manual_seed(4);
  ActorCritic network(ImageSpec(96), run::PpoConfig{});
  const std::vector<uint8_t> images = RandomImages(ImageSpec(96), 5, 1);
  const ObservationBatch batch{.flat = torch::zeros({5, 2}), .images = images};
  ActorCriticImpl::Pass pass;
  network->Forward(batch, /*for_backward=*/false, pass);
  EXPECT_EQ(pass.features.sizes(), torch::IntArrayRef({5, 256 + 2}));
  EXPECT_EQ(pass.head.rows(), 3);
  EXPECT_EQ(pass.head.cols(), 5);
  EXPECT_EQ(pass.values.rows(), 1);
  EXPECT_EQ(pass.values.cols(), 5);
  // The context reaches the heads: changing it changes the value.
  const Eigen::MatrixXf values = pass.values;
  network->Forward({.flat = torch::ones({5, 2}), .images = batch.images}, false, pass);
  EXPECT_FALSE((values.array() == pass.values.array()).all());
}

// The paper's CarRacing policy: the context through its own MLP (ReLU), whose output follows
// NatureCNN's features; a policy without context, or without image, has no branch.
TEST(ActorCriticTest, AContextBranchFeedsTheContextsOwnFeaturesToTheHeads) {
  torch::manual_seed(4);
  const run::PpoConfig config{.context_layers = {32, 8}};
  ActorCritic network(ImageSpec(96), config);
  EXPECT_EQ(network->named_parameters().find("context_1.weight")->sizes(),
            torch::IntArrayRef({8, 32}));
  const std::vector<uint8_t> images = RandomImages(ImageSpec(96), 5, 1);
  const ObservationBatch batch{.flat = torch::zeros({5, 2}), .images = images};
  ActorCriticImpl::Pass pass;
  network->Forward(batch, /*for_backward=*/false, pass);
  EXPECT_EQ(pass.features.sizes(), torch::IntArrayRef({5, 256 + 8}));
  const Eigen::MatrixXf values = pass.values;
  network->Forward({.flat = torch::ones({5, 2}), .images = batch.images}, false, pass);
  EXPECT_FALSE((values.array() == pass.values.array()).all());
  const actor::PolicyWeights exported = network->ExportActor();
  ASSERT_EQ(exported.context_layers.size(), 2u);
  EXPECT_EQ(exported.context_layers[0].activation, actor::Activation::kRelu);

  run::PolicySpec blind = ImageSpec(96);
  blind.context_size = 0;
  EXPECT_EQ(ActorCritic(blind, config)->named_parameters().find("context_0.weight"), nullptr);
  EXPECT_EQ(ActorCritic(CartPoleSpec(), config)->named_parameters().find("context_0.weight"),
            nullptr);
}

TEST(ActorCriticTest, PassesLeaveNoAutogradGraphOnTheirFeatures) {
  // Passes are made again and again: a graph recorded on what they keep would chain across
  // passes (growing without bound, then overflowing the stack when freed).
  torch::manual_seed(5);
  ActorCritic network(ImageSpec(36), run::PpoConfig{});
  ActorCriticImpl::Pass pass;
  const std::vector<uint8_t> images = RandomImages(ImageSpec(36), 8, 2);
  const ObservationBatch batch{.flat = torch::randn({8, 2}), .images = images};
  for (int i = 0; i < 2; ++i) {
    network->Forward(batch, /*for_backward=*/true, pass);
    network->Backward(pass, Eigen::MatrixXf::Ones(3, 8), Eigen::MatrixXf::Ones(1, 8),
                      std::vector<float>(3, 1.0f));
  }
  EXPECT_FALSE(pass.features.requires_grad());
  EXPECT_EQ(pass.features.grad_fn(), nullptr);
}

// NatureCNN's features of an image do not depend on how many images a pass takes at once:
// a forward pass not kept for backward goes in chunks of NatureCnn::kChunk images.
TEST(ActorCriticTest, ImageFeaturesAgreeWhateverTheChunking) {
  torch::manual_seed(6);
  ActorCritic network(ImageSpec(36), run::PpoConfig{});
  const int count = NatureCnn::kChunk + 5;
  const std::vector<uint8_t> images = RandomImages(ImageSpec(36), count, 3);
  const ObservationBatch batch{.flat = torch::zeros({count, 2}), .images = images};
  ActorCriticImpl::Pass chunked;
  network->Forward(batch, /*for_backward=*/false, chunked);
  ActorCriticImpl::Pass whole;
  network->Forward(batch, /*for_backward=*/true, whole);
  EXPECT_TRUE(chunked.image_features.isApprox(whole.image_features, 1e-6f));
  EXPECT_GT(chunked.image_features.cwiseAbs().maxCoeff(), 0.0f);
}

}  // namespace
}  // namespace dcs::learner
