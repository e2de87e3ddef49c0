// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_LEARNER_POLICY_SPECS_H_
#define DCS_TESTS_LEARNER_POLICY_SPECS_H_

// The policy shapes learner tests use, and images for them.

#include <cstdint>
#include <vector>

#include "common/random.h"
#include "run/ppo_config.h"

namespace dcs::learner {

// CartPole's: 4 observations and one context value, two actions.
inline run::PolicySpec CartPoleSpec() {
  return {.observation_size = 4, .context_size = 1, .num_actions = 2, .action_size = 1};
}

// BipedalWalker's: 24 observations and one context value, four continuous actions in [-1, 1].
inline run::PolicySpec WalkerSpec() {
  return {.observation_size = 24,
          .context_size = 1,
          .num_actions = 0,
          .action_size = 4,
          .action_low = {-1, -1, -1, -1},
          .action_high = {1, 1, 1, 1}};
}

// A side x side RGB image, two context values, three continuous actions (CarRacing's bounds).
inline run::PolicySpec ImageSpec(int side) {
  return {.image_height = side,
          .image_width = side,
          .image_channels = 3,
          .context_size = 2,
          .num_actions = 0,
          .action_size = 3,
          .action_low = {-1, 0, 0},
          .action_high = {1, 1, 1}};
}

// `count` images of `spec`'s shape of uniformly random bytes, channel last, image after image.
inline std::vector<uint8_t> RandomImages(const run::PolicySpec& spec, int count, uint64_t seed) {
  Random random(seed);
  std::vector<uint8_t> images(spec.image_size() * count);
  for (uint8_t& byte : images) byte = static_cast<uint8_t>(random.Integers(0, 256));
  return images;
}

}  // namespace dcs::learner

#endif  // DCS_TESTS_LEARNER_POLICY_SPECS_H_
