// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_POLICY_NETWORK_H_
#define DCS_ACTOR_POLICY_NETWORK_H_

// Policy inference in Eigen (no libtorch on actors): the actor half of Stable-Baselines3's
// policies, loaded from the learner's weights (actor/policy_weights.h). For vector
// observations, SB3's MlpPolicy: tanh hidden layers on the observation and context, then a
// linear head giving categorical logits or a Gaussian mean with a state-independent log-std.
// For images, its MultiInputPolicy: NatureCNN on the image (actor/image_encoder.h), the context
// appended, then the same layers. It computes the same function as the learner's torch network
// (tested to 1e-5); actors and `dcs train` both act with it, so they act alike bit for bit.
// Thread-compatible: one instance per thread.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "absl/status/statusor.h"
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
  int action_size() const { return discrete() ? 1 : static_cast<int>(log_std_.size()); }
  bool discrete() const { return num_actions_ > 0; }

  // The head's output for one input: logits (discrete) or the Gaussian mean (continuous).
  // REQUIRES: input.size() == input_size(), image.size() == image_size(), output.size() ==
  // head size.
  void Forward(std::span<const float> input, std::span<const uint8_t> image,
               std::span<float> output);

  // Policy: an action sampled from the policy's distribution (categorical, or mean + std *
  // N(0, 1)), unclipped; or its mode when `deterministic` (argmax, or the mean).
  void Act(std::span<const float> input, std::span<const uint8_t> image, bool deterministic,
           Random& random, std::span<float> action) override;

 private:
  PolicyNetwork() = default;

  // Runs the network; the head's output, valid until the next call.
  const Eigen::VectorXf& Run(std::span<const float> input, std::span<const uint8_t> image);

  struct Layer {
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weight;
    Eigen::VectorXf bias;
    Activation activation;
  };
  std::optional<ImageEncoder> encoder_;
  std::vector<Layer> layers_;
  Eigen::VectorXf log_std_;
  Eigen::VectorXf std_;
  int num_actions_ = 0;
  int input_size_ = 0;
  Eigen::VectorXf features_;                  // image policies: the encoding, then the input
  std::vector<Eigen::VectorXf> activations_;  // scratch, one per layer
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_POLICY_NETWORK_H_
