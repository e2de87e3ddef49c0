// Copyright 2026 The DCS Authors.
#include "actor/policy_network.h"

#include <algorithm>
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
    const Eigen::Map<const RowMajorMatrix> weight(layer.weight.data(), layer.outputs,
                                                  layer.inputs);
    Layer& dense = policy.layers_.emplace_back(
        Layer{.bias = Eigen::Map<const Eigen::VectorXf>(layer.bias.data(), layer.outputs),
              .activation = layer.activation});
    if (layer.outputs >= 8) {  // Eigen's packet of floats on x86-64-v3
      dense.by_columns = weight;
    } else {
      dense.by_rows = weight;
    }
    inputs = layer.outputs;
  }
  policy.head_size_ = inputs;
  if (weights.num_actions > 0 ? inputs != weights.num_actions
                              : inputs != static_cast<int>(weights.log_std.size())) {
    return absl::InvalidArgumentError(
        absl::StrCat("the policy head has ", inputs, " outputs for ",
                     weights.num_actions > 0 ? weights.num_actions
                                             : static_cast<int>(weights.log_std.size()),
                     " actions"));
  }
  policy.std_ = Eigen::Map<const Eigen::VectorXf>(weights.log_std.data(),
                                                  static_cast<int>(weights.log_std.size()))
                    .array()
                    .exp();
  policy.activations_.resize(policy.layers_.size());
  return policy;
}

void PolicyNetwork::Forward(int count, std::span<const float> inputs,
                            std::span<const uint8_t> images, std::span<float> head) {
  using ConstView = Eigen::Map<const Eigen::MatrixXf>;
  // The first layer's batch: the flat inputs as they are (sample after sample is column after
  // column), or for an image policy each image's features followed by its flat input.
  const float* first = inputs.data();
  int first_rows = input_size_;
  if (encoder_.has_value()) {
    const int encoded = encoder_->feature_size();
    features_.resize(encoded + input_size_, count);
    for (int i = 0; i < count; ++i) {
      float* column = features_.col(i).data();
      encoder_->Encode(images.subspan(static_cast<size_t>(i) * image_size(), image_size()),
                       std::span<float>(column, encoded));
      std::copy_n(inputs.begin() + static_cast<ptrdiff_t>(i) * input_size_, input_size_,
                  column + encoded);
    }
    first = features_.data();
    first_rows = static_cast<int>(features_.rows());
  }
  for (size_t l = 0; l < layers_.size(); ++l) {
    const Layer& layer = layers_[l];
    const ConstView input = l == 0 ? ConstView(first, first_rows, count)
                                   : ConstView(activations_[l - 1].data(),
                                               activations_[l - 1].rows(), count);
    if (layer.by_rows.size() > 0) {
      DenseForward(layer.by_rows, layer.bias, layer.activation, input, activations_[l]);
    } else {
      DenseForward(layer.by_columns, layer.bias, layer.activation, input, activations_[l]);
    }
  }
  // The head's outputs, [head_size x count]: sample after sample.
  std::copy_n(activations_.back().data(), static_cast<size_t>(count) * head_size_, head.begin());
}

void PolicyNetwork::Act(int count, std::span<const float> inputs, std::span<const uint8_t> images,
                        bool deterministic, std::span<Random> randoms, std::span<float> actions) {
  head_.resize(static_cast<size_t>(count) * head_size_);
  Forward(count, inputs, images, head_);
  const std::span<const float> std(std_.data(), std_.size());
  const int action = action_size();
  for (int i = 0; i < count; ++i) {
    SampleAction(std::span<const float>(head_).subspan(static_cast<size_t>(i) * head_size_,
                                                       head_size_),
                 std, num_actions_, deterministic ? nullptr : &randoms[i],
                 actions.subspan(static_cast<size_t>(i) * action, action));
  }
}

}  // namespace dcs::actor
