// Copyright 2026 The DCS Authors.
#include "learner/gae.h"

#include <cassert>

namespace dcs::learner {

void ComputeGae(const GaeInput& input, float gamma, float lambda, std::span<float> advantages,
                std::span<float> returns) {
  const int steps = input.num_steps;
  const int envs = input.num_envs;
  assert(advantages.size() == static_cast<size_t>(steps) * envs);
  assert(returns.size() == advantages.size());
  for (int e = 0; e < envs; ++e) {
    float last_gae = 0.0f;
    for (int t = steps - 1; t >= 0; --t) {
      const size_t i = static_cast<size_t>(t) * envs + e;
      float nonterminal;
      float next_value;
      if (t == steps - 1) {
        nonterminal = 1.0f - static_cast<float>(input.last_dones[e]);
        next_value = input.last_values[e];
      } else {
        nonterminal = 1.0f - static_cast<float>(input.episode_starts[i + envs]);
        next_value = input.values[i + envs];
      }
      const float delta = input.rewards[i] + gamma * next_value * nonterminal - input.values[i];
      last_gae = delta + gamma * lambda * nonterminal * last_gae;
      advantages[i] = last_gae;
      returns[i] = last_gae + input.values[i];
    }
  }
}

}  // namespace dcs::learner
