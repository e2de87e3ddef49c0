// Copyright 2026 The DCS Authors.
#include "actor/policy_network.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::actor {

absl::StatusOr<PolicyNetwork> PolicyNetwork::Create(const PolicyWeights& weights) {
  if (weights.layers.empty()) return absl::InvalidArgumentError("a policy needs layers");
  PolicyNetwork policy;
  policy.num_actions_ = weights.num_actions;
  int inputs = weights.layers.front().inputs;
  policy.input_size_ = inputs;
  if (weights.image.has_value()) {
    DCS_ASSIGN_OR_RETURN(policy.encoder_, ImageEncoder::Create(*weights.image));
    policy.input_size_ = inputs - policy.encoder_->feature_size();
    if (policy.input_size_ < 0) {
      return absl::InvalidArgumentError(absl::StrCat(
          "policy layer 0 takes ", inputs, " inputs, fewer than the image encoder's ",
          policy.encoder_->feature_size(), " features"));
    }
    policy.features_.resize(inputs);
  }
  for (size_t i = 0; i < weights.layers.size(); ++i) {
    const DenseLayer& layer = weights.layers[i];
    if (layer.inputs != inputs || layer.outputs < 1 ||
        layer.weight.size() != static_cast<size_t>(layer.inputs) * layer.outputs ||
        layer.bias.size() != static_cast<size_t>(layer.outputs)) {
      return absl::InvalidArgumentError(
          absl::StrCat("policy layer ", i, " does not fit: ", layer.inputs, " -> ",
                       layer.outputs, " after ", inputs, " outputs"));
    }
    Layer dense{.weight = Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic,
                                                         Eigen::RowMajor>>(
                    layer.weight.data(), layer.outputs, layer.inputs),
                .bias = Eigen::Map<const Eigen::VectorXf>(layer.bias.data(), layer.outputs),
                .activation = layer.activation};
    policy.layers_.push_back(std::move(dense));
    policy.activations_.emplace_back(layer.outputs);
    inputs = layer.outputs;
  }
  const int head = inputs;
  if (weights.num_actions > 0 ? head != weights.num_actions
                              : head != static_cast<int>(weights.log_std.size())) {
    return absl::InvalidArgumentError(
        absl::StrCat("the policy head has ", head, " outputs for ",
                     weights.num_actions > 0 ? weights.num_actions
                                             : static_cast<int>(weights.log_std.size()),
                     " actions"));
  }
  policy.log_std_ = Eigen::Map<const Eigen::VectorXf>(weights.log_std.data(),
                                                      static_cast<int>(weights.log_std.size()));
  policy.std_ = policy.log_std_.array().exp();
  return policy;
}

const Eigen::VectorXf& PolicyNetwork::Run(std::span<const float> input,
                                          std::span<const uint8_t> image) {
  if (encoder_.has_value()) {
    const int encoded = encoder_->feature_size();
    encoder_->Encode(image, std::span<float>(features_.data(), encoded));
    std::copy(input.begin(), input.end(), features_.data() + encoded);
  }
  for (size_t i = 0; i < layers_.size(); ++i) {
    const Layer& layer = layers_[i];
    Eigen::VectorXf& y = activations_[i];
    if (i > 0) {
      y.noalias() = layer.weight * activations_[i - 1];
    } else if (encoder_.has_value()) {
      y.noalias() = layer.weight * features_;
    } else {
      y.noalias() = layer.weight * Eigen::Map<const Eigen::VectorXf>(input.data(), input_size_);
    }
    y += layer.bias;
    switch (layer.activation) {
      case Activation::kNone:
        break;
      case Activation::kTanh:
        y = y.array().tanh();
        break;
      case Activation::kRelu:
        y = y.cwiseMax(0.0f);
        break;
    }
  }
  return activations_.back();
}

void PolicyNetwork::Forward(std::span<const float> input, std::span<const uint8_t> image,
                            std::span<float> output) {
  const Eigen::VectorXf& head = Run(input, image);
  std::copy(head.data(), head.data() + head.size(), output.begin());
}

void PolicyNetwork::Act(std::span<const float> input, std::span<const uint8_t> image,
                        bool deterministic, Random& random, std::span<float> action) {
  const Eigen::VectorXf& head = Run(input, image);
  SampleAction(std::span<const float>(head.data(), head.size()),
               std::span<const float>(std_.data(), std_.size()), num_actions_, deterministic,
               random, action);
}

}  // namespace dcs::actor
