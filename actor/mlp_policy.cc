// Copyright 2026 The DCS Authors.
#include "actor/mlp_policy.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace dcs::actor {

absl::StatusOr<MlpPolicy> MlpPolicy::Create(const MlpWeights& weights) {
  if (weights.layers.empty()) return absl::InvalidArgumentError("a policy needs layers");
  MlpPolicy policy;
  policy.num_actions_ = weights.num_actions;
  policy.input_size_ = weights.layers.front().inputs;
  int inputs = policy.input_size_;
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
                .tanh = layer.tanh};
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

const Eigen::VectorXf& MlpPolicy::Run(std::span<const float> input) {
  const Eigen::Map<const Eigen::VectorXf> x(input.data(), input_size_);
  for (size_t i = 0; i < layers_.size(); ++i) {
    const Layer& layer = layers_[i];
    Eigen::VectorXf& y = activations_[i];
    if (i == 0) {
      y.noalias() = layer.weight * x;
    } else {
      y.noalias() = layer.weight * activations_[i - 1];
    }
    y += layer.bias;
    if (layer.tanh) y = y.array().tanh();
  }
  return activations_.back();
}

void MlpPolicy::Forward(std::span<const float> input, std::span<float> output) {
  const Eigen::VectorXf& head = Run(input);
  std::copy(head.data(), head.data() + head.size(), output.begin());
}

void MlpPolicy::Act(std::span<const float> input, bool deterministic, Random& random,
                    std::span<float> action) {
  const Eigen::VectorXf& head = Run(input);
  SampleAction(std::span<const float>(head.data(), head.size()),
               std::span<const float>(std_.data(), std_.size()), num_actions_, deterministic,
               random, action);
}

}  // namespace dcs::actor
