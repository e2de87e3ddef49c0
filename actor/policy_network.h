// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_POLICY_NETWORK_H_
#define DCS_ACTOR_POLICY_NETWORK_H_

// Policy inference in Eigen (no libtorch on actors): the actor half of Stable-Baselines3's
// policies, loaded from the learner's weights (actor/policy_weights.h). For vector
// observations, SB3's MlpPolicy: tanh hidden layers on the observation and context, then a
// linear head giving categorical logits or a Gaussian mean with a state-independent log-std.
// For images, its MultiInputPolicy: NatureCNN on the image (actor/image_encoder.h), the context
// appended (as it is, or through its own branch of layers), then the same layers. It computes
// the same function as the learner's network (tested to 1e-5); actors and `dcs train` both act
// with it, so they act alike bit for bit.
//
// A batch of samples goes through each layer at once (actor/dense_forward.h), and each sample's
// outputs are a function of its own input alone, bit for bit, whatever the batch holds besides.
//
// Thread-compatible: one instance per thread (it owns its scratch).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/dense_forward.h"
#include "actor/image_encoder.h"
#include "actor/policy.h"
#include "actor/policy_weights.h"
#include "common/random.h"

namespace dcs::actor {

class PolicyNetwork final : public Policy {
 public:
  // INVALID_ARGUMENT if the layers do not chain or a size is wrong.
  static absl::StatusOr<PolicyNetwork> Create(const PolicyWeights& weights);

  // Floats of the flat input: the observation and context (image policies: the context).
  int input_size() const { return input_size_; }
  // Bytes of the image; 0 for a policy without one.
  int image_size() const { return encoder_.has_value() ? encoder_->image_size() : 0; }
  // Floats per action: 1 (an index) for discrete policies.
  int action_size() const { return discrete() ? 1 : static_cast<int>(std_.size()); }
  // Floats of the head's output: logits (discrete) or the Gaussian mean (continuous).
  int head_size() const { return head_size_; }
  bool discrete() const { return num_actions_ > 0; }

  // The head's outputs of `count` samples, sample by sample, into `head`.
  // REQUIRES: inputs.size() == count * input_size(), images.size() == count * image_size(),
  // head.size() == count * head_size().
  void Forward(int count, std::span<const float> inputs, std::span<const uint8_t> images,
               std::span<float> head);

  // Policy: actions sampled from the policy's distribution (categorical, or mean + std *
  // N(0, 1)), unclipped; or its mode when `deterministic` (argmax, or the mean).
  void Act(int count, std::span<const float> inputs, std::span<const uint8_t> images,
           bool deterministic, std::span<Random> randoms, std::span<float> actions) override;

 private:
  struct Layer {
    // The weight in one of two storage orders, whichever Eigen's matrix-vector kernel runs
    // faster for its shape: by columns when its outputs fill a vector register (one
    // multiply-add per input and register), else by rows (one dot product per output). The other
    // is empty.
    Eigen::MatrixXf by_columns;
    RowMajorMatrix by_rows;
    Eigen::VectorXf bias;
    Activation activation;
  };

  PolicyNetwork() = default;

  // `layer` as a Layer, if it takes `inputs`; `what` names it in the error.
  static absl::StatusOr<Layer> MakeLayer(const DenseLayer& layer, int inputs,
                                         absl::string_view what);
  // Each of `layers` on `input`, each layer's output into `outputs`.
  static void ForwardLayers(const std::vector<Layer>& layers,
                            Eigen::Map<const Eigen::MatrixXf> input,
                            std::vector<Eigen::MatrixXf>& outputs);

  std::optional<ImageEncoder> encoder_;
  std::vector<Layer> context_layers_;
  std::vector<Layer> layers_;
  Eigen::VectorXf std_;  // exp(log_std); continuous policies only
  int num_actions_ = 0;
  int input_size_ = 0;
  int head_size_ = 0;
  // Scratch: an image policy's first batch (image features, then the flat input or its
  // branch's output), each layer's output (the context branch's apart), and the head's outputs
  // of Act.
  Eigen::MatrixXf features_;
  std::vector<Eigen::MatrixXf> context_activations_;
  std::vector<Eigen::MatrixXf> activations_;
  std::vector<float> head_;
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_POLICY_NETWORK_H_
