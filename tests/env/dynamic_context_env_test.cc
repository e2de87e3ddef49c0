// Copyright 2026 The DCS Authors.
//
// The dynamic-context wrapper over CartPole (docs/reference.md, "Step timing",
// env/dynamic_context_env.h): step timing of schedule calls, observation modes and normalisation,
// pools re-applied at every reset, validation, and determinism.

// env/cartpole.h comes first: env/dynamic_context_env.h uses ContextSpace and
// NormalizeContext without including env/context_feature.h (not self-contained).
#include "env/cartpole.h"
#include "env/dynamic_context_env.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "env/context_pool.h"
#include "env/schedule.h"
#include "env/schedule_config.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::HasSubstr;
using Env = DynamicContextEnv<CartPole>;

constexpr int kLength = CartPole::kLength;

ScheduleSpec Spec(std::string family, std::map<std::string, ScheduleParam> params,
                  double min_value = 0.35, double max_value = 0.75, uint32_t seed = 1) {
  ScheduleConfig config;
  config.family = std::move(family);
  config.params = std::move(params);
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, min_value, max_value, seed);
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *spec : ScheduleSpec{};
}

// Sinusoid on [0.35, 0.75]: amplitude 0.5 * 0.4 / 2 = 0.1, period 20, down first.
ScheduleSpec Sine() {
  return Spec("sinusoidal", {{"amplitude_frac", 0.5},
                             {"period", 20.0},
                             {"initial_direction", std::string("down")}});
}

ScheduleSpec Up() {
  return Spec("continuous_incrementer", {{"delta", 0.01},
                                         {"episode_direction", std::string("up")},
                                         {"follow_predefined_prob", 1.0}});
}

FeatureSchedule Scheduled(int feature, ScheduleSpec spec) {
  return {.feature = feature, .stages = {{.steps = 1, .spec = std::move(spec)}}};
}

std::vector<double> ContextWithLength(double length) {
  std::vector<double> context = CartPole::Features().Defaults();
  context[kLength] = length;
  return context;
}

ContextPool Pool(std::vector<double> values) { return *ContextPool::OfValues(std::move(values)); }

float NormalizedLength(double length) {
  return NormalizeContext(CartPole::Features().feature(kLength), length);
}

// One transition as the wrapper took it: the episode and step, the state the action was taken
// in, the context the policy saw with it, and every feature's true value during it.
struct Transition {
  int64_t episode = 0;
  int64_t t = 0;
  std::array<float, 4> state = {};
  std::vector<float> visible;
  std::vector<double> context;
};

// A wrapper, its buffers, a simple balancing policy, and a record of every transition.
struct Slot {
  explicit Slot(Env e) : env(std::move(e)), context(env.context_size()) {}

  void Reset(int64_t global_step = 0) { env.Reset(global_step, observation, context); }
  StepResult Step() {
    const std::array<int32_t, 1> action = {observation[2] + 0.5f * observation[3] > 0 ? 1 : 0};
    Transition transition{.episode = env.episode(),
                          .t = env.episode_steps(),
                          .state = observation,
                          .visible = context};
    const StepResult result = env.Step(action, observation, context);
    // A schedule's value is written before the physics step, so after it the features still
    // hold the values the transition ran with.
    for (int i = 0; i < CartPole::kNumFeatures; ++i) transition.context.push_back(env.feature(i));
    transitions.push_back(std::move(transition));
    return result;
  }

  Env env;
  std::array<float, 4> observation = {};
  std::vector<float> context;
  std::vector<Transition> transitions;
};

Slot MakeSlot(DynamicContextOptions options) {
  absl::StatusOr<Env> env = Env::Create(std::move(options));
  EXPECT_TRUE(env.ok()) << env.status();
  return Slot(*std::move(env));
}

std::string CreateError(DynamicContextOptions options) {
  absl::StatusOr<Env> env = Env::Create(std::move(options));
  EXPECT_FALSE(env.ok());
  return env.ok() ? "" : std::string(env.status().message());
}

// ---------------------------------------------------------------------------------------------
// Step timing

TEST(DynamicContextEnvTest, FirstTransitionMakesNoScheduleCall) {
  Slot slot = MakeSlot({.context = ContextWithLength(0.55),
                        .schedules = {Scheduled(kLength, Sine())},
                        .observe = ObserveMode::kLive,
                        .observed_features = {kLength}});
  slot.Reset();
  const std::array<float, 4> first_state = slot.observation;
  for (int t = 0; t < 30; ++t) slot.Step();
  ASSERT_EQ(slot.transitions.size(), 30u);
  EXPECT_EQ(slot.env.episode(), 0);
  EXPECT_EQ(slot.env.episode_steps(), 30);

  // Transition 1 (t = 0) runs with the reset value; transition t + 1 with call k = t.
  EXPECT_EQ(slot.transitions[0].context[kLength], 0.55);
  for (size_t t = 1; t < slot.transitions.size(); ++t) {
    EXPECT_NEAR(slot.transitions[t].context[kLength],
                0.55 - 0.1 * std::sin(2 * std::numbers::pi * static_cast<double>(t) / 20), 1e-12)
        << t;
  }
  EXPECT_NE(slot.transitions[1].context[kLength], 0.55);
  // The policy saw, with s_t, the context shown after the previous transition (live value).
  EXPECT_FLOAT_EQ(slot.transitions[0].visible[0], NormalizedLength(0.55));
  for (size_t t = 1; t < slot.transitions.size(); ++t) {
    EXPECT_FLOAT_EQ(slot.transitions[t].visible[0],
                    NormalizedLength(slot.transitions[t - 1].context[kLength]));
  }
  // The recorded state is the one the action was taken in; other features are untouched.
  EXPECT_THAT(slot.transitions[0].state, ::testing::ElementsAreArray(first_state));
  for (size_t t = 0; t < slot.transitions.size(); ++t) {
    EXPECT_EQ(slot.transitions[t].episode, 0);
    EXPECT_EQ(slot.transitions[t].t, static_cast<int64_t>(t));
    EXPECT_EQ(slot.transitions[t].context[CartPole::kGravity], 9.8);
  }
}

TEST(DynamicContextEnvTest, FirstCallSkipFamiliesChangeFromTheThirdTransition) {
  Slot slot = MakeSlot({.context = ContextWithLength(0.5),
                        .schedules = {Scheduled(kLength, Up())},
                        .observe = ObserveMode::kNone});
  slot.Reset();
  for (int t = 0; t < 6; ++t) slot.Step();
  EXPECT_EQ(slot.transitions[0].context[kLength], 0.5);  // no call
  EXPECT_EQ(slot.transitions[1].context[kLength], 0.5);  // k = 1: the skip
  for (size_t t = 2; t < 6; ++t) {
    EXPECT_NEAR(slot.transitions[t].context[kLength], 0.5 + 0.01 * static_cast<double>(t - 1),
                1e-12);
  }
}

TEST(DynamicContextEnvTest, EventAtCallKHappensInTransitionKPlusOne) {
  // Event times compare with k, so a jump due at k = 10 happens in the 11th transition.
  const ScheduleSpec jump =
      Spec("sudden_jump", {{"step_size_range", std::vector<double>{0.05, 0.05}},
                           {"interval_range", std::vector<double>{10, 10}},
                           {"direction", std::string("positive")}});
  Slot slot = MakeSlot({.context = ContextWithLength(0.5),
                        .schedules = {Scheduled(kLength, jump)},
                        .observe = ObserveMode::kNone});
  slot.Reset();
  for (int t = 0; t < 25; ++t) slot.Step();
  const std::vector<Transition>& record = slot.transitions;
  for (size_t t = 0; t < 10; ++t) EXPECT_EQ(record[t].context[kLength], 0.5) << t;
  for (size_t t = 10; t < 20; ++t) EXPECT_NEAR(record[t].context[kLength], 0.55, 1e-12) << t;
  for (size_t t = 20; t < 25; ++t) EXPECT_NEAR(record[t].context[kLength], 0.6, 1e-12) << t;
}

TEST(DynamicContextEnvTest, ScheduleRunsWithItsOwnSeedEpisodeAndSlot) {
  // The wrapper's feature trajectory is the schedule's own for (episode, slot), fed back the
  // current value.
  const ScheduleSpec walk = Spec("random_walk", {{"std_frac", 0.02}}, 0.35, 0.75, 17);
  Slot slot = MakeSlot({.context = ContextWithLength(0.55),
                        .schedules = {Scheduled(kLength, walk)},
                        .observe = ObserveMode::kNone,
                        .slot = 3});
  auto alone = MakeSchedule(walk);
  for (uint64_t episode = 0; episode < 3; ++episode) {
    slot.Reset();
    double expected = alone->Reset(0.55, {.episode = episode, .slot = 3});
    ASSERT_EQ(slot.env.feature(kLength), expected);
    slot.Step();
    for (int k = 1; k <= 25; ++k) {
      slot.Step();
      expected = alone->Next(k, expected);
      ASSERT_EQ(slot.env.feature(kLength), expected) << episode << " " << k;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Observation modes and normalisation

TEST(DynamicContextEnvTest, LiveModeShowsThePostUpdateValueNormalised) {
  Slot slot = MakeSlot({.context = ContextWithLength(0.55),
                        .schedules = {Scheduled(kLength, Sine())},
                        .observe = ObserveMode::kLive,
                        .observed_features = {kLength}});
  ASSERT_EQ(slot.env.context_size(), 1);
  slot.Reset();
  // Sensor bounds (0.05, 2.0): mid 1.025, half 0.975.
  EXPECT_NEAR(slot.context[0], (0.55 - 1.025) / 0.975, 1e-6);
  slot.Step();
  EXPECT_NEAR(slot.context[0], (0.55 - 1.025) / 0.975, 1e-6);
  slot.Step();  // call k = 1 before this physics step: the observation shows its value
  const double updated = 0.55 - 0.1 * std::sin(2 * std::numbers::pi / 20);
  EXPECT_NEAR(slot.env.feature(kLength), updated, 1e-12);
  EXPECT_NEAR(slot.context[0], (updated - 1.025) / 0.975, 1e-6);
}

TEST(DynamicContextEnvTest, NormalisationClipsAtFive) {
  // gravity 100 with sensor bounds (0.1, 25): (100 - 12.55) / 12.45 = 7.02 -> 5.
  // initial_state_lower -10 / upper 10 with sensor bounds (-1, 1): -10 -> -5, 10 -> 5.
  std::vector<double> context = CartPole::Features().Defaults();
  context[CartPole::kGravity] = 100;
  context[CartPole::kInitialStateLower] = -10;
  context[CartPole::kInitialStateUpper] = 10;
  context[kLength] = 0.55;
  Slot slot = MakeSlot({.context = context,
                        .observe = ObserveMode::kLive,
                        .observed_features = {CartPole::kGravity, CartPole::kInitialStateLower,
                                              CartPole::kInitialStateUpper, kLength}});
  slot.Reset();
  EXPECT_EQ(slot.context[0], 5.0f);
  EXPECT_EQ(slot.context[1], -5.0f);
  EXPECT_EQ(slot.context[2], 5.0f);
  EXPECT_NEAR(slot.context[3], (0.55 - 1.025) / 0.975, 1e-6);  // order as observed_features
}

TEST(DynamicContextEnvTest, InitialModeShowsTheEpisodesInitialValueAllEpisode) {
  Slot slot = MakeSlot({.pools = {{.feature = kLength, .pool = Pool({0.45, 0.65})}},
                        .selection = ContextPool::Selection::kRoundRobin,
                        .schedules = {Scheduled(kLength, Sine())},
                        .observe = ObserveMode::kInitial,
                        .observed_features = {kLength}});
  for (double initial : {0.45, 0.65}) {
    slot.Reset();
    const float shown = NormalizedLength(initial);
    EXPECT_FLOAT_EQ(slot.context[0], shown);
    for (int t = 0; t < 15; ++t) {
      slot.Step();
      EXPECT_FLOAT_EQ(slot.context[0], shown) << t;
    }
    EXPECT_NE(slot.env.feature(kLength), initial);  // the feature did move
  }
}

TEST(DynamicContextEnvTest, NoneModeShowsNothing) {
  Slot slot = MakeSlot({.context = ContextWithLength(0.55),
                        .schedules = {Scheduled(kLength, Sine())},
                        .observe = ObserveMode::kNone});
  EXPECT_EQ(slot.env.context_size(), 0);
  slot.Reset();
  slot.Step();
  slot.Step();
  EXPECT_NE(slot.env.feature(kLength), 0.55);  // the schedule still runs
}

// ---------------------------------------------------------------------------------------------
// Pools, and re-applying the context at every reset

TEST(DynamicContextEnvTest, PoolValueIsReappliedAtEveryResetEvenAfterDrift) {
  Slot slot = MakeSlot({.pools = {{.feature = kLength, .pool = Pool({0.4, 0.6})}},
                        .selection = ContextPool::Selection::kRoundRobin,
                        .schedules = {Scheduled(kLength, Up())},
                        .observe = ObserveMode::kLive,
                        .observed_features = {kLength}});
  for (int episode = 0; episode < 4; ++episode) {
    slot.Reset();
    const double initial = episode % 2 == 0 ? 0.4 : 0.6;
    EXPECT_EQ(slot.env.feature(kLength), initial) << episode;
    EXPECT_FLOAT_EQ(slot.context[0], NormalizedLength(initial));
    for (int t = 0; t < 12; ++t) slot.Step();
    EXPECT_NEAR(slot.env.feature(kLength), initial + 0.10, 1e-12);  // drifted by 10 steps
  }
  EXPECT_EQ(slot.env.episode(), 3);
}

TEST(DynamicContextEnvTest, SingleValuePoolAndBaseContextAreReappliedToo) {
  // A single-value pool is one value here (the reference lists it twice): every episode starts
  // at 0.5.
  Slot pooled = MakeSlot({.pools = {{.feature = kLength, .pool = Pool({0.5})}},
                          .schedules = {Scheduled(kLength, Up())},
                          .observe = ObserveMode::kNone});
  // Without a pool the scheduled feature starts each episode at the configured context.
  Slot base = MakeSlot({.context = ContextWithLength(0.45),
                        .schedules = {Scheduled(kLength, Up())},
                        .observe = ObserveMode::kNone});
  for (int episode = 0; episode < 3; ++episode) {
    pooled.Reset();
    base.Reset();
    EXPECT_EQ(pooled.env.feature(kLength), 0.5);
    EXPECT_EQ(base.env.feature(kLength), 0.45);
    for (int t = 0; t < 10; ++t) {
      pooled.Step();
      base.Step();
    }
    EXPECT_GT(pooled.env.feature(kLength), 0.5);
    EXPECT_GT(base.env.feature(kLength), 0.45);
  }
}

TEST(DynamicContextEnvTest, EpisodeRandomnessFollowsTheNamedStreams) {
  // Pool draws from StreamSeed(run_seed, "pool", {slot, episode}); the environment's reset
  // from StreamSeed(run_seed, "reset", {slot, episode}).
  const ContextPool pool = *ContextPool::OfSize(0.35, 0.75, 7);
  Slot slot = MakeSlot({.pools = {{.feature = kLength, .pool = pool}},
                        .selection = ContextPool::Selection::kRandom,
                        .observe = ObserveMode::kNone,
                        .run_seed = 9,
                        .slot = 2});
  std::set<double> lengths;
  for (uint64_t episode = 0; episode < 20; ++episode) {
    slot.Reset();
    Random pool_random(StreamSeed(9, "pool", {2, episode}));
    const double expected =
        pool.Select(ContextPool::Selection::kRandom, episode, 2, pool_random);
    EXPECT_EQ(slot.env.feature(kLength), expected);
    lengths.insert(expected);
    CartPole reference;
    reference.SetFeature(kLength, expected);
    Random reset_random(StreamSeed(9, "reset", {2, episode}));
    std::array<float, 4> observation;
    reference.Reset(reset_random, observation);
    EXPECT_EQ(slot.observation, observation);
    for (float x : slot.observation) EXPECT_LE(std::abs(x), 0.1f);
  }
  EXPECT_GE(lengths.size(), 4u);  // the draws vary (7 values, 20 draws)
}

// ---------------------------------------------------------------------------------------------
// Multi-stage schedules

TEST(DynamicContextEnvTest, GlobalStepSelectsTheStageAtReset) {
  FeatureSchedule staged = {.feature = kLength,
                            .stages = {{.steps = 100, .spec = Spec("constant", {})},
                                       {.steps = 100, .spec = Up()}}};
  Slot slot = MakeSlot({.context = ContextWithLength(0.5),
                        .schedules = {staged},
                        .observe = ObserveMode::kNone});
  slot.Reset(/*global_step=*/99);
  for (int t = 0; t < 10; ++t) slot.Step();
  EXPECT_EQ(slot.env.feature(kLength), 0.5);
  slot.Reset(/*global_step=*/100);
  for (int t = 0; t < 10; ++t) slot.Step();
  EXPECT_NEAR(slot.env.feature(kLength), 0.58, 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Validation

TEST(DynamicContextEnvTest, CreateErrors) {
  // Pool value outside the feature's physical bounds [0.05, 5].
  EXPECT_THAT(CreateError({.pools = {{.feature = kLength, .pool = Pool({0.5, 6.0})}}}),
              HasSubstr("length"));
  // Schedule bounds outside the feature's bounds.
  EXPECT_THAT(CreateError({.schedules = {Scheduled(kLength, Spec("random_walk", {}, 0.01, 0.75))}}),
              HasSubstr("length"));
  // A feature scheduled, pooled or observed twice.
  EXPECT_THAT(CreateError({.schedules = {Scheduled(kLength, Sine()), Scheduled(kLength, Up())}}),
              HasSubstr("two schedules"));
  EXPECT_THAT(CreateError({.pools = {{.feature = kLength, .pool = Pool({0.5})},
                                     {.feature = kLength, .pool = Pool({0.6})}}}),
              HasSubstr("two pools"));
  EXPECT_THAT(CreateError({.observe = ObserveMode::kLive, .observed_features = {kLength, kLength}}),
              HasSubstr("length"));
  // Observe mode vs observed features.
  EXPECT_THAT(CreateError({.observe = ObserveMode::kLive}), HasSubstr("live"));
  EXPECT_THAT(CreateError({.observe = ObserveMode::kInitial}), HasSubstr("initial"));
  EXPECT_THAT(CreateError({.observe = ObserveMode::kNone, .observed_features = {kLength}}),
              HasSubstr("none"));
  // Feature indices that do not exist.
  EXPECT_THAT(CreateError({.pools = {{.feature = 42, .pool = Pool({0.5})}}}), HasSubstr("42"));
  EXPECT_THAT(CreateError({.schedules = {Scheduled(-1, Sine())}}), HasSubstr("-1"));
  EXPECT_THAT(CreateError({.observe = ObserveMode::kLive, .observed_features = {8}}),
              HasSubstr("8"));
  // Contexts: wrong size, invalid values.
  EXPECT_THAT(CreateError({.context = {0.5, 1.0}}), HasSubstr("8"));
  std::vector<double> bad = CartPole::Features().Defaults();
  bad[CartPole::kGravity] = -1;
  EXPECT_THAT(CreateError({.context = bad}), HasSubstr("gravity"));
  bad = CartPole::Features().Defaults();
  bad[CartPole::kInitialStateLower] = 0.2;
  EXPECT_THAT(CreateError({.context = bad}), HasSubstr("initial_state"));
  // Stages: none.
  EXPECT_THAT(CreateError({.schedules = {{.feature = kLength, .stages = {}}}}), HasSubstr("stage"));
  // A valid one, for contrast.
  EXPECT_TRUE(Env::Create({.pools = {{.feature = kLength, .pool = Pool({0.35, 0.75})}},
                           .schedules = {Scheduled(kLength, Sine())},
                           .observe = ObserveMode::kLive,
                           .observed_features = {kLength}})
                  .ok());
}

// ---------------------------------------------------------------------------------------------
// Determinism

DynamicContextOptions Stochastic(uint64_t slot) {
  return {.pools = {{.feature = kLength, .pool = *ContextPool::OfSize(0.35, 0.75, 7)}},
          .schedules = {Scheduled(kLength, Spec("random_walk", {{"std_frac", 0.02}}))},
          .observe = ObserveMode::kLive,
          .observed_features = {kLength},
          .run_seed = 123,
          .slot = slot};
}

struct Trace {
  std::vector<float> observations;
  std::vector<float> contexts;
  std::vector<double> rewards;
  std::vector<double> lengths;
  bool operator==(const Trace&) const = default;
};

Trace RunEpisodes(Slot& slot, int episodes, int steps) {
  Trace trace;
  for (int e = 0; e < episodes; ++e) {
    slot.Reset();
    for (int t = 0; t < steps; ++t) {
      const StepResult result = slot.Step();
      trace.observations.insert(trace.observations.end(), slot.observation.begin(),
                                slot.observation.end());
      trace.contexts.insert(trace.contexts.end(), slot.context.begin(), slot.context.end());
      trace.rewards.push_back(result.reward);
      trace.lengths.push_back(slot.env.feature(kLength));
    }
  }
  return trace;
}

TEST(DynamicContextEnvTest, IdenticalWrappersGiveIdenticalEpisodes) {
  Slot a = MakeSlot(Stochastic(0));
  Slot b = MakeSlot(Stochastic(0));
  const Trace ta = RunEpisodes(a, 4, 40);
  EXPECT_TRUE(ta == RunEpisodes(b, 4, 40));
  // Another slot runs other episodes.
  Slot c = MakeSlot(Stochastic(1));
  const Trace tc = RunEpisodes(c, 4, 40);
  EXPECT_NE(ta.observations, tc.observations);
  EXPECT_NE(ta.lengths, tc.lengths);
}

}  // namespace
}  // namespace dcs::env
