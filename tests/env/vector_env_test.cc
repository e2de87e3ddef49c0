// Copyright 2026 The DCS Authors.
//
// VectorEnv over CartPole (env/vector_env.h): batched stepping, SB3-style auto-reset with the
// final observation and context kept, global step counting and multi-stage switching.

// env/cartpole.h comes first: env/dynamic_context_env.h (included by env/vector_env.h) uses
// ContextSpace and NormalizeContext without including env/context_feature.h.
#include "env/cartpole.h"
#include "env/vector_env.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "env/context_pool.h"
#include "env/schedule_config.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::ElementsAreArray;
using ::testing::HasSubstr;
using Vec = VectorEnv<CartPole>;

constexpr int kLength = CartPole::kLength;

ScheduleSpec Spec(std::string family, std::map<std::string, ScheduleParam> params = {}) {
  ScheduleConfig config;
  config.family = std::move(family);
  config.params = std::move(params);
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, 0.35, 0.75, 1);
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *spec : ScheduleSpec{};
}

ScheduleSpec Up() {
  return Spec("continuous_incrementer", {{"delta", 0.001},
                                         {"episode_direction", std::string("up")},
                                         {"follow_predefined_prob", 1.0}});
}

float NormalizedLength(double length) {
  return NormalizeContext(CartPole::Features().feature(kLength), length);
}

Vec Make(std::vector<DynamicContextOptions> slots) {
  absl::StatusOr<Vec> vec = Vec::Create(std::move(slots));
  EXPECT_TRUE(vec.ok()) << vec.status();
  return *std::move(vec);
}

bool Terminal(std::span<const float> observation) {
  return std::abs(observation[0]) > CartPole::kXThreshold ||
         std::abs(observation[2]) > CartPole::kThetaThreshold;
}

// Slot i's pool is round robin over {0.4, 0.7}, observed live.
DynamicContextOptions PooledSlot(uint64_t slot) {
  return {.pools = {{.feature = kLength, .pool = *ContextPool::OfValues({0.4, 0.7})}},
          .selection = ContextPool::Selection::kRoundRobin,
          .observe = ObserveMode::kLive,
          .observed_features = {kLength},
          .run_seed = 5,
          .slot = slot};
}

TEST(VectorEnvTest, ResetFillsEveryRow) {
  Vec vec = Make({PooledSlot(0), PooledSlot(1), PooledSlot(2)});
  ASSERT_EQ(vec.size(), 3);
  ASSERT_EQ(vec.context_size(), 1);
  vec.Reset();
  EXPECT_EQ(vec.global_steps(), 0);
  ASSERT_EQ(vec.observations().size(), 12u);
  ASSERT_EQ(vec.contexts().size(), 3u);
  // Round robin rotated by slot: slot 0 starts at 0.4, slot 1 at 0.7, slot 2 at 0.4.
  EXPECT_FLOAT_EQ(vec.contexts()[0], NormalizedLength(0.4));
  EXPECT_FLOAT_EQ(vec.contexts()[1], NormalizedLength(0.7));
  EXPECT_FLOAT_EQ(vec.contexts()[2], NormalizedLength(0.4));
  for (int i = 0; i < 3; ++i) {
    CartPole reference;
    Random random(StreamSeed(5, "reset", {static_cast<uint64_t>(i), 0}));
    std::array<float, 4> observation;
    reference.Reset(random, observation);
    EXPECT_THAT(vec.observations().subspan(4 * i, 4), ElementsAreArray(observation)) << i;
  }
}

TEST(VectorEnvTest, AutoResetKeepsTheFinalObservationAndContext) {
  Vec vec = Make({PooledSlot(0), PooledSlot(1)});
  vec.Reset();
  const std::vector<int32_t> push_right = {1, 1};
  std::array<int, 2> finished_at = {0, 0};
  for (int step = 1; step <= 200 && (finished_at[0] == 0 || finished_at[1] == 0); ++step) {
    std::array<double, 2> length_before = {vec.slot(0).feature(kLength),
                                           vec.slot(1).feature(kLength)};
    vec.Step(push_right);
    EXPECT_EQ(vec.global_steps(), 2 * step);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(vec.rewards()[i], 1.0f);  // every step up to and including the terminating one
      if (finished_at[i] != 0 || !vec.terminated()[i]) {
        if (finished_at[i] == 0) {
          EXPECT_EQ(vec.slot(i).episode(), 0);
        }
        continue;
      }
      finished_at[i] = step;
      SCOPED_TRACE(i);
      EXPECT_FALSE(vec.truncated()[i]);
      // The final row is the terminal observation and the finished episode's context.
      EXPECT_TRUE(Terminal(vec.final_observations().subspan(4 * i, 4)));
      EXPECT_FLOAT_EQ(vec.final_contexts()[i], NormalizedLength(length_before[i]));
      // The slot has reset: episode 1 with the next pool value and a fresh first observation.
      EXPECT_EQ(vec.slot(i).episode(), 1);
      EXPECT_EQ(vec.slot(i).episode_steps(), 0);
      const double next_length = i == 0 ? 0.7 : 0.4;
      EXPECT_EQ(vec.slot(i).feature(kLength), next_length);
      EXPECT_FLOAT_EQ(vec.contexts()[i], NormalizedLength(next_length));
      CartPole reference;
      Random random(StreamSeed(5, "reset", {static_cast<uint64_t>(i), 1}));
      std::array<float, 4> first;
      reference.Reset(random, first);
      EXPECT_THAT(vec.observations().subspan(4 * i, 4), ElementsAreArray(first));
      EXPECT_FALSE(Terminal(vec.observations().subspan(4 * i, 4)));
    }
  }
  // Pushing right always topples the pole within a few dozen steps.
  EXPECT_GT(finished_at[0], 0);
  EXPECT_GT(finished_at[1], 0);
}

TEST(VectorEnvTest, TruncationAtTheTimeLimit) {
  // From the upright state exactly (reset bounds 0) a simple balancing policy survives the
  // 500-step limit: the 500th step is truncated, not terminated.
  std::vector<double> context = CartPole::Features().Defaults();
  context[CartPole::kInitialStateLower] = 0;
  context[CartPole::kInitialStateUpper] = 0;
  Vec vec = Make({{.context = context}});
  vec.Reset();
  for (int step = 1; step <= 500; ++step) {
    const std::span<const float> o = vec.observations();
    const std::vector<int32_t> action = {o[2] + 0.5f * o[3] > 0 ? 1 : 0};
    vec.Step(action);
    ASSERT_FALSE(vec.terminated()[0]) << step;
    if (step < 500) {
      ASSERT_FALSE(vec.truncated()[0]) << step;
    }
  }
  EXPECT_TRUE(vec.truncated()[0]);
  EXPECT_EQ(vec.rewards()[0], 1.0f);
  EXPECT_EQ(vec.slot(0).episode(), 1);
  EXPECT_EQ(vec.global_steps(), 500);
  // The final observation is the state after 500 steps; the new one is the upright reset.
  EXPECT_NE(vec.final_observations()[0], 0.0f);
  EXPECT_THAT(vec.observations(), ElementsAreArray({0.0f, 0.0f, 0.0f, 0.0f}));
}

TEST(VectorEnvTest, StageBoundaryTakesEffectAtTheFirstResetAfterIt) {
  // Probe the first episode's length L under the constant stage, then put the boundary in its
  // middle: the first episode (started at 0) keeps the constant schedule throughout; the next
  // one starts at global step L >= boundary and drifts.
  auto options = [](int64_t boundary) -> DynamicContextOptions {
    std::vector<double> context = CartPole::Features().Defaults();
    context[kLength] = 0.5;
    return {.context = context,
            .schedules = {{.feature = kLength,
                           .stages = {{.steps = boundary, .spec = Spec("constant")},
                                      {.steps = 1000, .spec = Up()}}}},
            .run_seed = 3};
  };
  const std::vector<int32_t> push_right = {1};
  Vec probe = Make({options(1000000)});
  probe.Reset();
  int length = 0;
  while (probe.slot(0).episode() == 0 && length < 500) {
    probe.Step(push_right);
    ++length;
  }
  ASSERT_GT(length, 4);
  ASSERT_LT(length, 500);

  Vec vec = Make({options(length / 2)});
  vec.Reset();
  for (int step = 1; step < length; ++step) {
    vec.Step(push_right);
    EXPECT_EQ(vec.slot(0).feature(kLength), 0.5) << step;  // past the boundary mid-episode
  }
  vec.Step(push_right);
  ASSERT_TRUE(vec.terminated()[0]);
  EXPECT_EQ(vec.global_steps(), length);
  // The new episode runs the second stage: after the skip, +0.001 per call.
  for (int step = 0; step < 3; ++step) vec.Step(push_right);
  ASSERT_EQ(vec.slot(0).episode(), 1);
  EXPECT_NEAR(vec.slot(0).feature(kLength), 0.501, 1e-12);
}

TEST(VectorEnvTest, GlobalStepsCountEverySlot) {
  Vec vec = Make({PooledSlot(0), PooledSlot(1), PooledSlot(2), PooledSlot(3)});
  vec.Reset();
  const std::vector<int32_t> actions = {0, 1, 0, 1};
  for (int step = 1; step <= 7; ++step) {
    vec.Step(actions);
    EXPECT_EQ(vec.global_steps(), 4 * step);
  }
}

TEST(VectorEnvTest, CreateErrors) {
  EXPECT_FALSE(Vec::Create({}).ok());
  // Slots must observe the same number of context values.
  absl::StatusOr<Vec> mismatched = Vec::Create({PooledSlot(0), {.slot = 1}});
  ASSERT_FALSE(mismatched.ok());
  EXPECT_THAT(mismatched.status().message(), HasSubstr("slot 1"));
  EXPECT_THAT(mismatched.status().message(), HasSubstr("same"));
  // A slot's own error is reported with its index.
  DynamicContextOptions bad = PooledSlot(2);
  bad.pools[0].pool = *ContextPool::OfValues({9.0});  // length above its bound 5
  absl::StatusOr<Vec> invalid = Vec::Create({PooledSlot(0), PooledSlot(1), bad});
  ASSERT_FALSE(invalid.ok());
  EXPECT_THAT(invalid.status().message(), HasSubstr("slot 2"));
  EXPECT_THAT(invalid.status().message(), HasSubstr("length"));
}

TEST(VectorEnvTest, ContextFreeSlotsHaveEmptyContextBuffers) {
  Vec vec = Make({{.slot = 0}, {.slot = 1}});
  EXPECT_EQ(vec.context_size(), 0);
  vec.Reset();
  EXPECT_TRUE(vec.contexts().empty());
  const std::vector<int32_t> push_right = {1, 1};
  for (int step = 0; step < 100; ++step) vec.Step(push_right);  // several auto-resets
  EXPECT_GE(vec.slot(0).episode(), 1);
  // Different slots, different initial states.
  EXPECT_NE(std::vector<float>(vec.observations().begin(), vec.observations().begin() + 4),
            std::vector<float>(vec.observations().begin() + 4, vec.observations().end()));
}

}  // namespace
}  // namespace dcs::env
