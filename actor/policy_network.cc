// Copyright 2026 The DCS Authors.
#include "actor/policy_network.h"

#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::actor {

absl::StatusOr<PolicyNetwork::Layer> PolicyNetwork::MakeLayer(const DenseLayer& layer,
                                                                int inputs,
                                                                absl::string_view what) {
  if (layer.inputs != inputs || layer.outputs < 1 ||
      layer.weight.size() != static_cast<size_t>(layer.inputs) * layer.outputs ||
      layer.bias.size() != static_cast<size_t>(layer.outputs)) {
    return absl::InvalidArgumentError(absl::StrCat(what, " does not fit: ", layer.inputs,
                                                   " -> ", layer.outputs, " after ", inputs,
                                                   " outputs"));
  }
  const Eigen::Map<const RowMajorMatrix> weight(layer.weight.data(), layer.outputs, layer.inputs);
  Layer dense{.bias = Eigen::Map<const Eigen::VectorXf>(layer.bias.data(), layer.outputs),
              .activation = layer.activation};
  if (layer.outputs >= 8) {  // Eigen's packet of floats on x86-64-v3
    dense.by_columns = weight;
  } else {
    dense.by_rows = weight;
  }
  return dense;
}

absl::StatusOr<PolicyNetwork> PolicyNetwork::Create(const PolicyWeights& weights) {
  if (weights.layers.empty()) return absl::InvalidArgumentError("a policy needs layers");
  if (!weights.context_layers.empty() && !weights.image.has_value()) {
    return absl::InvalidArgumentError("a context branch needs an image policy");
  }
  PolicyNetwork policy;
  policy.num_actions_ = weights.num_actions;
  int inputs = weights.layers.front().inputs;
  policy.input_size_ = inputs;
  if (weights.image.has_value()) {
    DCS_ASSIGN_OR_RETURN(policy.encoder_, ImageEncoder::Create(*weights.image));
    // What the branch, or else the flat input, adds to the encoder's features.
    const int joined = inputs - policy.encoder_->feature_size();
    if (joined < 0) {
      return absl::InvalidArgumentError(absl::StrCat(
          "policy layer 0 takes ", inputs, " inputs, fewer than the image encoder's ",
          policy.encoder_->feature_size(), " features"));
    }
    policy.input_size_ = joined;
    if (!weights.context_layers.empty()) {
      policy.input_size_ = weights.context_layers.front().inputs;  // the context's size
      int branch_inputs = policy.input_size_;
      for (size_t i = 0; i < weights.context_layers.size(); ++i) {
        DCS_ASSIGN_OR_RETURN(
            policy.context_layers_.emplace_back(),
            MakeLayer(weights.context_layers[i], branch_inputs, absl::StrCat("context layer ", i)));
        branch_inputs = weights.context_layers[i].outputs;
      }
      if (branch_inputs != joined) {
        return absl::InvalidArgumentError(
            absl::StrCat("the context branch gives ", branch_inputs, " features; policy layer 0 ",
                         "takes ", joined, " after the image encoder's"));
      }
      policy.context_activations_.resize(policy.context_layers_.size());
    }
  }
  for (size_t i = 0; i < weights.layers.size(); ++i) {
    DCS_ASSIGN_OR_RETURN(policy.layers_.emplace_back(),
                         MakeLayer(weights.layers[i], inputs, absl::StrCat("policy layer ", i)));
    inputs = weights.layers[i].outputs;
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

void PolicyNetwork::ForwardLayers(const std::vector<Layer>& layers,
                                  Eigen::Map<const Eigen::MatrixXf> input,
                                  std::vector<Eigen::MatrixXf>& outputs) {
  using ConstView = Eigen::Map<const Eigen::MatrixXf>;
  for (size_t l = 0; l < layers.size(); ++l) {
    const Layer& layer = layers[l];
    const ConstView layer_input =
        l == 0 ? input
               : ConstView(outputs[l - 1].data(), outputs[l - 1].rows(), outputs[l - 1].cols());
    if (layer.by_rows.size() > 0) {
      DenseForward(layer.by_rows, layer.bias, layer.activation, layer_input, outputs[l]);
    } else {
      DenseForward(layer.by_columns, layer.bias, layer.activation, layer_input, outputs[l]);
    }
  }
}

void PolicyNetwork::Forward(int count, std::span<const float> inputs,
                            std::span<const uint8_t> images, std::span<float> head) {
  using ConstView = Eigen::Map<const Eigen::MatrixXf>;
  // The first layer's batch: the flat inputs as they are (sample after sample is column after
  // column), or for an image policy each image's features followed by its flat input, or by the
  // context branch's output for it.
  const float* first = inputs.data();
  Eigen::Index first_rows = input_size_;
  if (encoder_.has_value()) {
    const float* joined = inputs.data();
    Eigen::Index joined_rows = input_size_;
    if (!context_layers_.empty()) {
      ForwardLayers(context_layers_, ConstView(inputs.data(), input_size_, count),
                    context_activations_);
      joined = context_activations_.back().data();
      joined_rows = context_activations_.back().rows();
    }
    const int encoded = encoder_->feature_size();
    features_.resize(encoded + joined_rows, count);
    for (int i = 0; i < count; ++i) {
      float* column = features_.col(i).data();
      encoder_->Encode(images.subspan(static_cast<size_t>(i) * image_size(), image_size()),
                       std::span<float>(column, encoded));
      std::copy_n(joined + i * joined_rows, joined_rows, column + encoded);
    }
    first = features_.data();
    first_rows = features_.rows();
  }
  ForwardLayers(layers_, ConstView(first, first_rows, count), activations_);
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
