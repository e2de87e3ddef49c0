// Copyright 2026 The DCS Authors.
#include "actor/image_encoder.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "actor/conv_layout.h"

namespace dcs::actor {

absl::StatusOr<ImageEncoder> ImageEncoder::Create(const ImageEncoderWeights& weights) {
  if (weights.height < 1 || weights.width < 1 || weights.channels < 1 || weights.convs.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat("an image encoder needs an image and convolutions, got ", weights.height,
                     "x", weights.width, "x", weights.channels, " and ", weights.convs.size(),
                     " convolutions"));
  }
  ImageEncoder encoder;
  encoder.image_size_ = weights.height * weights.width * weights.channels;
  int height = weights.height;
  int width = weights.width;
  int channels = weights.channels;
  encoder.activations_.emplace_back(height * width, channels);
  Eigen::Index largest_patch = 0;
  for (size_t i = 0; i < weights.convs.size(); ++i) {
    const ConvLayer& layer = weights.convs[i];
    const int k = layer.kernel;
    if (layer.in_channels != channels || layer.out_channels < 1 || k < 1 || layer.stride < 1 ||
        k > height || k > width ||
        layer.weight.size() != static_cast<size_t>(layer.out_channels) * channels * k * k ||
        layer.bias.size() != static_cast<size_t>(layer.out_channels)) {
      return absl::InvalidArgumentError(absl::StrCat(
          "convolution ", i, " does not fit: ", layer.in_channels, " -> ", layer.out_channels,
          " channels, kernel ", k, ", stride ", layer.stride, ", on ", height, "x", width, "x",
          channels));
    }
    Conv conv{.kernel = k,
              .stride = layer.stride,
              .in_width = width,
              .out_height = (height - k) / layer.stride + 1,
              .out_width = (width - k) / layer.stride + 1,
              .bias = Eigen::Map<const Eigen::VectorXf>(layer.bias.data(), layer.out_channels)};
    ToChannelLast(layer.weight, layer.out_channels, channels, k, conv.weight);
    largest_patch = std::max(largest_patch, conv.weight.cols());
    height = conv.out_height;
    width = conv.out_width;
    channels = layer.out_channels;
    encoder.activations_.emplace_back(height * width, channels);
    encoder.convs_.push_back(std::move(conv));
  }
  encoder.patch_.resize(largest_patch);

  const DenseLayer& linear = weights.linear;
  const int positions = height * width;
  if (linear.inputs != positions * channels || linear.outputs < 1 ||
      linear.weight.size() != static_cast<size_t>(linear.inputs) * linear.outputs ||
      linear.bias.size() != static_cast<size_t>(linear.outputs) ||
      linear.activation != Activation::kRelu) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the encoder's linear layer does not fit: ", linear.inputs, " -> ", linear.outputs,
        " after ", positions * channels, " outputs (it must be followed by ReLU)"));
  }
  encoder.linear_weight_.resize(linear.outputs, linear.inputs);
  for (int out = 0; out < linear.outputs; ++out) {
    for (int c = 0; c < channels; ++c) {
      for (int p = 0; p < positions; ++p) {
        encoder.linear_weight_(out, p * channels + c) =
            linear.weight[static_cast<size_t>(out) * linear.inputs + c * positions + p];
      }
    }
  }
  encoder.linear_bias_ = Eigen::Map<const Eigen::VectorXf>(linear.bias.data(), linear.outputs);
  return encoder;
}

void ImageEncoder::Encode(std::span<const uint8_t> image, std::span<float> features) {
  // torch's images.to(float).div(255), element by element.
  std::transform(image.begin(), image.end(), activations_.front().data(),
                 [](uint8_t byte) { return static_cast<float>(byte) / 255.0f; });
  for (size_t i = 0; i < convs_.size(); ++i) {
    const Conv& conv = convs_[i];
    const Matrix& in = activations_[i];
    Matrix& out = activations_[i + 1];
    const Eigen::Index channels = in.cols();
    const Eigen::Index run = conv.kernel * channels;  // one row of the receptive field
    const auto patch = patch_.head(conv.weight.cols());
    for (int oy = 0; oy < conv.out_height; ++oy) {
      for (int ox = 0; ox < conv.out_width; ++ox) {
        for (int ky = 0; ky < conv.kernel; ++ky) {
          const float* row =
              in.data() + ((oy * conv.stride + ky) * conv.in_width + ox * conv.stride) * channels;
          std::copy_n(row, run, patch_.data() + ky * run);
        }
        Eigen::Map<Eigen::VectorXf> y(out.data() + (oy * conv.out_width + ox) * out.cols(),
                                      out.cols());
        y.noalias() = conv.weight * patch;
        y = (y + conv.bias).cwiseMax(0.0f);
      }
    }
  }
  const Matrix& last = activations_.back();
  Eigen::Map<Eigen::VectorXf> y(features.data(), feature_size());
  y.noalias() = linear_weight_ * Eigen::Map<const Eigen::VectorXf>(last.data(), last.size());
  y = (y + linear_bias_).cwiseMax(0.0f);
}

}  // namespace dcs::actor
