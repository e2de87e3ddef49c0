// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_MLP_POLICY_H_
#define DCS_ACTOR_MLP_POLICY_H_

// Policy inference on actors for MLP policies, in Eigen (no libtorch on the hot path): the
// actor half of Stable-Baselines3's MlpPolicy (tanh hidden layers, then a linear head giving
// categorical logits or a Gaussian mean with a state-independent log-std), loaded from the
// learner's weights. It computes the same function as the learner's torch network (tested to
// 1e-5). Thread-compatible: one instance per thread.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "absl/status/statusor.h"
#include "actor/policy.h"
#include "common/random.h"

namespace dcs::actor {

// One dense layer: y = W x + b, then tanh if `tanh`.
struct DenseLayer {
  int inputs = 0;
  int outputs = 0;
  std::vector<float> weight;  // outputs x inputs, row-major (torch's Linear layout)
  std::vector<float> bias;    // outputs
  bool tanh = true;
};

// The actor network as the learner exports it: hidden layers, then the head (no tanh).
struct MlpWeights {
  std::vector<DenseLayer> layers;
  std::vector<float> log_std;  // continuous actions only, one per action dimension
  int num_actions = 0;         // discrete: the number of actions; continuous: 0
};

class MlpPolicy final : public Policy {
 public:
  // INVALID_ARGUMENT if the layers do not chain or a size is wrong.
  static absl::StatusOr<MlpPolicy> Create(const MlpWeights& weights);

  int input_size() const { return input_size_; }
  // Floats per action: 1 (an index) for discrete policies.
  int action_size() const { return discrete() ? 1 : static_cast<int>(log_std_.size()); }
  bool discrete() const { return num_actions_ > 0; }

  // The head's output for one input: logits (discrete) or the Gaussian mean (continuous).
  // REQUIRES: input.size() == input_size(), output.size() == head size.
  void Forward(std::span<const float> input, std::span<float> output);

  // An action sampled from the policy's distribution (categorical, or mean + std * N(0, 1)),
  // unclipped; or its mode when `deterministic` (argmax, or the mean).
  void Act(std::span<const float> input, bool deterministic, Random& random,
           std::span<float> action);
  // Policy: as above; an MLP policy has no image.
  void Act(std::span<const float> input, std::span<const uint8_t> /*image*/, bool deterministic,
           Random& random, std::span<float> action) override {
    Act(input, deterministic, random, action);
  }

 private:
  MlpPolicy() = default;

  // Runs the network on `input`; the head's output, valid until the next call.
  const Eigen::VectorXf& Run(std::span<const float> input);

  struct Layer {
    Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> weight;
    Eigen::VectorXf bias;
    bool tanh;
  };
  std::vector<Layer> layers_;
  Eigen::VectorXf log_std_;
  Eigen::VectorXf std_;
  int num_actions_ = 0;
  int input_size_ = 0;
  std::vector<Eigen::VectorXf> activations_;  // scratch, one per layer
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_MLP_POLICY_H_
