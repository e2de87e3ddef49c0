// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_PPO_LOSS_H_
#define DCS_LEARNER_PPO_LOSS_H_

// Stable-Baselines3's PPO loss on one minibatch (ppo/ppo.py, train), and its gradient with
// respect to the network's outputs, computed sample by sample in plain C++. The network's
// own backward pass (learner/actor_critic.h) takes the gradient from there: on networks this
// small, recording the loss's few dozen tensor operations for autograd cost more than the
// minibatch's matrix products.
//
//   ratio   = exp(log_prob - old_log_prob)
//   policy  = -mean(min(A * ratio, A * clamp(ratio, 1 - clip, 1 + clip)))
//   value   = mean((V' - R)^2), V' = V, or old_V + clamp(V - old_V, -clip_vf, clip_vf)
//   entropy = -mean(H)
//   loss    = policy + vf_coef * value + ent_coef * entropy
//
// Where torch's derivatives have a choice the gradient makes torch's: min's gradient goes to
// the unclipped term when the two are equal (torch splits it, which sums to the same), and
// clamp passes the gradient at its bounds.
//
// Distributions: categorical over logits (log_softmax), or a diagonal Gaussian with a
// state-independent log-std, log-probability and entropy summed over action dimensions.
// Per-sample values are float32, as torch's; means and statistics are accumulated in double.
// Thread-safe (pure functions).

#include <span>

#include "run/ppo_config.h"

namespace dcs::learner {

// One minibatch of B samples. `head`: [B][A] logits (A = num_actions) or Gaussian means
// (A = action_size); `actions`: [B][action_size], a discrete action as its index.
struct PpoLossInput {
  int size = 0;
  std::span<const float> head;
  std::span<const float> values;
  std::span<const float> log_std;  // [action_size], Gaussian policies only
  std::span<const float> actions;
  std::span<const float> advantages;  // normalised if the config asks
  std::span<const float> returns;
  std::span<const float> old_log_probs;
  std::span<const float> old_values;
};

// Means over the minibatch, as SB3 logs them.
struct PpoLoss {
  double policy = 0;
  double value = 0;
  double entropy = 0;
  double total = 0;
  double approx_kl = 0;      // mean((ratio - 1) - log ratio), SB3's estimator
  double clip_fraction = 0;  // share of |ratio - 1| > clip
};

// d total / d head ([B][A]), d values ([B]) and d log_std ([action_size]; empty for
// categorical policies). Overwritten.
struct PpoLossGradient {
  std::span<float> head;
  std::span<float> values;
  std::span<float> log_std;
};

// REQUIRES: spec and config valid; every span sized as documented.
PpoLoss ComputePpoLoss(const run::PolicySpec& spec, const run::PpoConfig& config,
                       const PpoLossInput& input, const PpoLossGradient& gradient);

// log pi(action | head) of each of `log_probs.size()` samples, as in PpoLossInput.
void ActionLogProbs(const run::PolicySpec& spec, std::span<const float> head,
                    std::span<const float> log_std, std::span<const float> actions,
                    std::span<float> log_probs);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_PPO_LOSS_H_
