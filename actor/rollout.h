// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_ROLLOUT_H_
#define DCS_ACTOR_ROLLOUT_H_

// One rollout of experience as actors deliver it: num_steps transitions of num_envs
// environment slots, struct-of-arrays, time-major ([t][e] is step t of slot e). Actors send only
// what they observed and did; the learner computes values and log-probabilities itself.
// Thread-compatible (plain data).

#include <cstdint>
#include <vector>

namespace dcs::actor {

struct Rollout {
  int num_steps = 0;
  int num_envs = 0;
  // The policy's inputs at s_t: [t][e][flat_input_size] floats (observation, then context),
  // and for image policies [t][e][height * width * channels] bytes.
  std::vector<float> inputs;
  std::vector<uint8_t> images;
  std::vector<float> actions;  // [t][e][action_size]; unclipped samples (discrete: the index)
  std::vector<float> rewards;  // [t][e]
  std::vector<uint8_t> episode_starts;  // [t][e]: s_t is an episode's first observation

  // Steps cut by the time limit (truncated and not terminated): their final observation, whose
  // value is bootstrapped into the step's reward.
  struct Truncation {
    int step = 0;
    int env = 0;
    std::vector<float> input;
    std::vector<uint8_t> image;
  };
  std::vector<Truncation> truncations;

  // After the last step: each slot's next input and whether that step ended its episode.
  std::vector<float> last_inputs;  // [e][flat_input_size]
  std::vector<uint8_t> last_images;
  std::vector<uint8_t> last_dones;  // [e]
};

}  // namespace dcs::actor

#endif  // DCS_ACTOR_ROLLOUT_H_
