// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_LEARNER_SMALL_RUN_H_
#define DCS_TESTS_LEARNER_SMALL_RUN_H_

// The learner tests' run, and run configs for them. Thread-safe.

#include "absl/strings/string_view.h"
#include "gtest/gtest.h"
#include "run/run_spec.h"
#include "run/run_spec_yaml.h"

namespace dcs::learner {

// A CartPole run small enough for a unit test: 10 rollouts of 64 steps per slot (128 steps
// with the two slots), evaluated every 256 steps and at the stage boundary 400 on two
// contexts; pool-3 and a two-stage schedule so that resuming has pools, schedules and episodes
// crossing rollout boundaries to get right.
inline constexpr char kSmallRun[] = R"(
env: cartpole
seed: 11
total_timesteps: 1280
n_envs: 2
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
stages:
  - {steps: 400, schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}}
  - {steps: 880, schedule: {family: random_walk, std_frac: 0.05}}
observe: live
evaluation: {freq: 256, episodes: 2, contexts: {id: [0.5], ood_high: [1.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)";

// A CarRacing run (an image policy: NatureCNN) small enough for a unit test: 3 rollouts of 32
// steps of two slots, one evaluation episode at the end.
inline constexpr char kSmallImageRun[] = R"(
env: car_racing
seed: 5
total_timesteps: 192
n_envs: 2
feature: COM_Y
training_range: [-0.8, 0.8]
pool: {size: 3}
observe: live
evaluation: {freq: 1000, episodes: 1, contexts: {id: [0.0]}}
ppo: {n_steps: 32, batch_size: 32, n_epochs: 2}
)";

// The run config in `yaml`; a test failure if it does not parse.
inline run::RunSpec Spec(absl::string_view yaml) {
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(yaml, "test.yaml");
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.value_or(run::RunSpec());
}

}  // namespace dcs::learner

#endif  // DCS_TESTS_LEARNER_SMALL_RUN_H_
