// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_LEARNER_SMALL_RUN_H_
#define DCS_TESTS_LEARNER_SMALL_RUN_H_

// The learner tests' run, and run configs for them. Thread-safe.

#include <cstdint>
#include <string>

#include "absl/strings/str_format.h"
#include "absl/strings/string_view.h"
#include "gtest/gtest.h"
#include "run/run_spec.h"
#include "run/run_spec_yaml.h"

namespace dcs::learner {

// The sizes of a CartPoleRun.
struct CartPoleRunSizes {
  uint64_t seed = 0;
  int64_t total_timesteps = 0;
  int n_envs = 0;
  int64_t first_stage_steps = 0;  // the sinusoid's; the random walk's are the rest
  int64_t evaluation_freq = 0;
  int evaluation_episodes = 0;
  int n_steps = 0;
  int batch_size = 0;
};

// A CartPole run of `sizes` with every part a handover or a resume could get wrong: pool-3 and
// a two-stage schedule (a sinusoid, then a random walk), so that pools, schedules and episodes
// cross rollout boundaries; evaluations on two contexts, at every `evaluation_freq` steps and
// at the stage boundary.
inline std::string CartPoleRun(const CartPoleRunSizes& sizes) {
  return absl::StrFormat(R"(env: cartpole
seed: %d
total_timesteps: %d
n_envs: %d
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
stages:
  - {steps: %d, schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}}
  - {steps: %d, schedule: {family: random_walk, std_frac: 0.05}}
observe: live
evaluation: {freq: %d, episodes: %d, contexts: {id: [0.5], ood_high: [1.0]}}
ppo: {n_steps: %d, batch_size: %d, n_epochs: 2}
)",
                         sizes.seed, sizes.total_timesteps, sizes.n_envs, sizes.first_stage_steps,
                         sizes.total_timesteps - sizes.first_stage_steps, sizes.evaluation_freq,
                         sizes.evaluation_episodes, sizes.n_steps, sizes.batch_size);
}

// A CartPole run small enough for a unit test: 10 rollouts of 64 steps per slot (128 steps
// with the two slots), evaluated every 256 steps and at the stage boundary 400.
inline const std::string kSmallRun = CartPoleRun(
    {.seed = 11, .total_timesteps = 1280, .n_envs = 2, .first_stage_steps = 400,
     .evaluation_freq = 256, .evaluation_episodes = 2, .n_steps = 64, .batch_size = 32});

// The sizes of a CarRacingRun.
struct CarRacingRunSizes {
  uint64_t seed = 0;
  int64_t evaluation_freq = 0;
  int n_steps = 0;                // also the batch size: one batch per epoch
  bool context_branch = false;    // the context through its own layers (context_layers)
};

// A CarRacing run (an image policy: NatureCNN) of 192 steps of two slots, small enough for a
// unit test, its evaluations of one episode on one context.
inline std::string CarRacingRun(const CarRacingRunSizes& sizes) {
  return absl::StrFormat(R"(env: car_racing
seed: %d
total_timesteps: 192
n_envs: 2
feature: COM_Y
training_range: [-0.8, 0.8]
pool: {size: 3}
observe: live
evaluation: {freq: %d, episodes: 1, contexts: {id: [0.0]}}
ppo: {n_steps: %d, batch_size: %d, n_epochs: 2%s}
)",
                         sizes.seed, sizes.evaluation_freq, sizes.n_steps, sizes.n_steps,
                         sizes.context_branch ? ", context_layers: [16]" : "");
}

// 3 rollouts of 32 steps, one evaluation at the end.
inline const std::string kSmallImageRun =
    CarRacingRun({.seed = 5, .evaluation_freq = 1000, .n_steps = 32});

// The run config in `yaml`; a test failure if it does not parse.
inline run::RunSpec Spec(absl::string_view yaml) {
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(yaml, "test.yaml");
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.value_or(run::RunSpec());
}

}  // namespace dcs::learner

#endif  // DCS_TESTS_LEARNER_SMALL_RUN_H_
