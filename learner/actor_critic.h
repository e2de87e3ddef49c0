// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_ACTOR_CRITIC_H_
#define DCS_LEARNER_ACTOR_CRITIC_H_

// Stable-Baselines3's ActorCriticPolicy in libtorch (spec/ppo.md §3): separate policy and
// value MLPs with tanh (default [64, 64] each) on the features, a linear action head
// (categorical logits, or a Gaussian mean with a state-independent log-std) and a linear
// value head; orthogonal initialisation with SB3's gains (sqrt 2 for the feature extractor
// and the MLPs, 0.01 for the action head, 1 for the value head) and zero biases.
// Features: the flat observation and context as they are; or, for an image observation,
// SB3's CombinedExtractor: NatureCNN (256 features) on the image / 255, then the context
// appended.
//
// Internal to learner/: only learner translation units include libtorch headers.
// Confined to one thread (libtorch is pinned to one thread per run).

#include <torch/torch.h>

#include <vector>

#include "actor/policy_weights.h"
#include "run/ppo_config.h"

namespace dcs::learner {

// A batch of observations as tensors: `flat` [B, flat_input_size] float; `images`
// [B, channels, height, width] float in [0, 1] (undefined without an image).
struct ObservationBatch {
  torch::Tensor flat;
  torch::Tensor images;
};

class ActorCriticImpl : public torch::nn::Module {
 public:
  // REQUIRES: spec and config valid. Initialises from torch's global generator (seed it first).
  ActorCriticImpl(const run::PolicySpec& spec, const run::PpoConfig& config);

  // The action head's output: logits [B, num_actions] or the Gaussian mean [B, action_size].
  torch::Tensor ActionHead(const ObservationBatch& batch);
  // V(s) [B].
  torch::Tensor Value(const ObservationBatch& batch);

  struct Evaluation {
    torch::Tensor values;     // [B]
    torch::Tensor log_probs;  // [B], summed over action dimensions
    torch::Tensor entropy;    // [B]
  };
  // SB3's evaluate_actions: `actions` [B, action_size], float (discrete: [B, 1] indices as
  // kLong, as ActionIndices makes them). Without
  // `entropy_gradient` the entropy is computed outside autograd (for logging only: with
  // ent_coef 0 it adds nothing to the gradient, and each recorded operation costs time).
  Evaluation EvaluateActions(const ObservationBatch& batch, const torch::Tensor& actions,
                             bool entropy_gradient = true);

  // Discrete actions stored as floats, as EvaluateActions takes them: [B, 1] kLong.
  static torch::Tensor ActionIndices(const torch::Tensor& actions) {
    return actions.to(torch::kLong);
  }

  // The actor half, for Eigen inference (actor/policy_network.h).
  actor::PolicyWeights ExportActor() const;

  const torch::Tensor& log_std() const { return log_std_; }

 private:
  torch::Tensor Features(const ObservationBatch& batch);

  const run::PolicySpec spec_;
  // Linear layers each followed by tanh, called directly: torch::nn::Sequential's type-erased
  // dispatch costs more than these layers compute.
  struct TanhMlp {
    std::vector<torch::nn::Linear> layers;
    torch::Tensor Forward(torch::Tensor x);
  };

  torch::nn::Sequential cnn_{nullptr};  // NatureCNN, image observations only
  TanhMlp pi_;
  TanhMlp vf_;
  torch::nn::Linear action_net_{nullptr};
  torch::nn::Linear value_net_{nullptr};
  torch::Tensor log_std_;  // continuous actions only
};
TORCH_MODULE(ActorCritic);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_ACTOR_CRITIC_H_
