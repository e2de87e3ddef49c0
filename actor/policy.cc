// Copyright 2026 The DCS Authors.
#include "actor/policy.h"

#include <algorithm>
#include <cmath>

namespace dcs::actor {

void SampleAction(std::span<const float> head, std::span<const float> std, int num_actions,
                  Random* random, std::span<float> action) {
  const int size = static_cast<int>(head.size());
  if (num_actions == 0) {
    for (int i = 0; i < size; ++i) {
      action[i] = random == nullptr
                      ? head[i]
                      : head[i] + std[i] * static_cast<float>(random->Normal(0, 1));
    }
    return;
  }
  const int best = static_cast<int>(std::max_element(head.begin(), head.end()) - head.begin());
  if (random == nullptr) {
    action[0] = static_cast<float>(best);
    return;
  }
  // Inverse-CDF sampling from softmax(logits), shifted by the maximum for stability.
  double total = 0;
  for (float logit : head) total += std::exp(static_cast<double>(logit - head[best]));
  double u = random->Uniform01() * total;
  int chosen = size - 1;
  for (int i = 0; i < size; ++i) {
    u -= std::exp(static_cast<double>(head[i] - head[best]));
    if (u < 0) {
      chosen = i;
      break;
    }
  }
  action[0] = static_cast<float>(chosen);
}

}  // namespace dcs::actor
