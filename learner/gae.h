// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_GAE_H_
#define DCS_LEARNER_GAE_H_

// Generalised advantage estimation with episode boundaries, exactly as Stable-Baselines3's
// RolloutBuffer.compute_returns_and_advantage (common/buffers.py), in float32 as its buffers are.
// Thread-safe (a pure function).
//
// Buffers are time-major, [num_steps][num_envs]: element t * num_envs + e is step t of env e.
// For t = T-1 down to 0, with last_gae = 0:
//   nonterminal = 1 - (t == T-1 ? last_dones[e] : episode_starts[t+1][e])
//   next_value  = t == T-1 ? last_values[e] : values[t+1][e]
//   delta       = rewards[t][e] + gamma * next_value * nonterminal - values[t][e]
//   last_gae    = delta + gamma * lambda * nonterminal * last_gae
//   advantages[t][e] = last_gae;  returns[t][e] = last_gae + values[t][e]
// A time-limit cut is bootstrapped before this, by adding gamma * V(final observation) to the
// reward of the truncated step (SB3's collect_rollouts, common/on_policy_algorithm.py).

#include <cstdint>
#include <span>

namespace dcs::learner {

struct GaeInput {
  int num_steps = 0;
  int num_envs = 0;
  std::span<const float> rewards;          // [T][E]
  std::span<const float> values;           // [T][E], V(s_t) at collection
  std::span<const uint8_t> episode_starts; // [T][E], 1 if s_t is an episode's first observation
  std::span<const float> last_values;      // [E], V of the observation after the last step
  std::span<const uint8_t> last_dones;     // [E], 1 if the last step ended an episode
};

// REQUIRES: every [T][E] span has num_steps * num_envs elements, the [E] spans num_envs.
void ComputeGae(const GaeInput& input, float gamma, float lambda, std::span<float> advantages,
                std::span<float> returns);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_GAE_H_
