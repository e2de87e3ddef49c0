// Copyright 2026 The DCS Authors.
//
// Multi-stage schedules (docs/reference.md, "Multi-stage schedules", env/staged_schedule.h): stage
// boundaries in global environment steps, taking effect at the next reset.

#include "env/staged_schedule.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "env/schedule.h"
#include "env/schedule_config.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::HasSubstr;

ScheduleSpec Spec(std::string family, std::map<std::string, ScheduleParam> params,
                  uint32_t seed = 1) {
  ScheduleConfig config;
  config.family = std::move(family);
  config.params = std::move(params);
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, 0, 1, seed);
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *spec : ScheduleSpec{};
}

ScheduleSpec Constant() { return Spec("constant", {}); }

// Steps up by 0.01 every call after the first.
ScheduleSpec Up() {
  return Spec("continuous_incrementer", {{"delta", 0.01},
                                         {"episode_direction", std::string("up")},
                                         {"follow_predefined_prob", 1.0}});
}

StagedSchedule Make(std::vector<ScheduleStage> stages) {
  absl::StatusOr<StagedSchedule> staged = StagedSchedule::Create(std::move(stages));
  EXPECT_TRUE(staged.ok()) << staged.status();
  return *std::move(staged);
}

TEST(StagedScheduleTest, StageAtBoundaries) {
  const StagedSchedule staged = Make({{.steps = 100, .spec = Constant()},
                                      {.steps = 50, .spec = Up()},
                                      {.steps = 200, .spec = Constant()}});
  EXPECT_EQ(staged.StageAt(0), 0);
  EXPECT_EQ(staged.StageAt(99), 0);   // the last step of stage 1
  EXPECT_EQ(staged.StageAt(100), 1);  // the first step of stage 2
  EXPECT_EQ(staged.StageAt(149), 1);
  EXPECT_EQ(staged.StageAt(150), 2);
  EXPECT_EQ(staged.StageAt(349), 2);
  EXPECT_EQ(staged.StageAt(350), 2);  // past the end: the last stage stays
  EXPECT_EQ(staged.StageAt(int64_t{1} << 40), 2);
}

TEST(StagedScheduleTest, PaperCartPoleStages) {
  // K = 4 stages of 30k / 30k / 45k / 45k steps.
  const StagedSchedule staged = Make({{.steps = 30000, .spec = Constant()},
                                      {.steps = 30000, .spec = Constant()},
                                      {.steps = 45000, .spec = Constant()},
                                      {.steps = 45000, .spec = Constant()}});
  EXPECT_EQ(staged.StageAt(29999), 0);
  EXPECT_EQ(staged.StageAt(30000), 1);
  EXPECT_EQ(staged.StageAt(59999), 1);
  EXPECT_EQ(staged.StageAt(60000), 2);
  EXPECT_EQ(staged.StageAt(104999), 2);
  EXPECT_EQ(staged.StageAt(105000), 3);
  EXPECT_EQ(staged.StageAt(150000), 3);
}

TEST(StagedScheduleTest, StageChangesAtTheNextResetNeverMidEpisode) {
  StagedSchedule staged = Make({{.steps = 100, .spec = Constant()}, {.steps = 100, .spec = Up()}});
  EXPECT_EQ(staged.stage(), -1);  // none before the first reset

  // An episode starting at step 90 runs stage 1 (constant) to its end, however long.
  double v = staged.Reset(0.5, {.episode = 0}, 90);
  EXPECT_EQ(staged.stage(), 0);
  EXPECT_EQ(v, 0.5);
  for (int k = 1; k <= 50; ++k) {
    v = staged.Next(k, v);
    EXPECT_EQ(v, 0.5) << k;
  }
  EXPECT_EQ(staged.stage(), 0);

  // The next reset, past the boundary, switches to stage 2.
  v = staged.Reset(0.5, {.episode = 1}, 140);
  EXPECT_EQ(staged.stage(), 1);
  v = staged.Next(1, v);
  EXPECT_EQ(v, 0.5);  // the incrementer's first-call skip
  v = staged.Next(2, v);
  EXPECT_NEAR(v, 0.51, 1e-12);

  // Resets within the same stage keep it; the last stage stays past the end.
  staged.Reset(0.5, {.episode = 2}, 199);
  EXPECT_EQ(staged.stage(), 1);
  staged.Reset(0.5, {.episode = 3}, 5000);
  EXPECT_EQ(staged.stage(), 1);
}

TEST(StagedScheduleTest, ResetAtExactlyTheBoundaryUsesTheNewStage) {
  StagedSchedule staged = Make({{.steps = 100, .spec = Up()}, {.steps = 100, .spec = Constant()}});
  staged.Reset(0.5, {}, 99);
  EXPECT_EQ(staged.stage(), 0);
  staged.Reset(0.5, {.episode = 1}, 100);
  EXPECT_EQ(staged.stage(), 1);
  double v = 0.5;
  for (int k = 1; k <= 5; ++k) v = staged.Next(k, v);
  EXPECT_EQ(v, 0.5);
}

TEST(StagedScheduleTest, NewStageDrawsFromItsOwnSeedAndTheRunningEpisodeCount) {
  // The second stage's episode 7 of slot 2 is exactly what the stage's schedule alone gives
  // for that (episode, slot).
  const ScheduleSpec walk = Spec("random_walk", {{"std_frac", 0.05}}, 99);
  StagedSchedule staged = Make({{.steps = 10, .spec = Constant()}, {.steps = 10, .spec = walk}});
  staged.Reset(0.5, {.episode = 6, .slot = 2}, 0);
  std::vector<double> from_staged = {staged.Reset(0.5, {.episode = 7, .slot = 2}, 10)};
  auto alone = MakeSchedule(walk);
  std::vector<double> from_alone = {alone->Reset(0.5, {.episode = 7, .slot = 2})};
  for (int k = 1; k <= 30; ++k) {
    from_staged.push_back(staged.Next(k, from_staged.back()));
    from_alone.push_back(alone->Next(k, from_alone.back()));
  }
  EXPECT_EQ(from_staged, from_alone);
  EXPECT_NE(from_staged.back(), 0.5);
}

TEST(StagedScheduleTest, SingleStageIsTheOrdinarySchedule) {
  const ScheduleSpec walk = Spec("random_walk", {{"std_frac", 0.05}}, 3);
  StagedSchedule staged = Make({{.steps = 1, .spec = walk}});
  auto alone = MakeSchedule(walk);
  for (uint64_t episode = 0; episode < 3; ++episode) {
    double a = staged.Reset(0.4, {.episode = episode}, static_cast<int64_t>(episode) * 1000);
    double b = alone->Reset(0.4, {.episode = episode});
    for (int k = 1; k <= 20; ++k) {
      a = staged.Next(k, a);
      b = alone->Next(k, b);
      ASSERT_EQ(a, b);
    }
  }
}

TEST(StagedScheduleTest, Errors) {
  EXPECT_THAT(StagedSchedule::Create({}).status().message(), HasSubstr("stage"));
  EXPECT_THAT(
      StagedSchedule::Create({{.steps = 10, .spec = Constant()}, {.steps = 0, .spec = Up()}})
          .status()
          .message(),
      HasSubstr("stage 2"));
  EXPECT_FALSE(StagedSchedule::Create({{.steps = -5, .spec = Constant()}}).ok());
  EXPECT_TRUE(StagedSchedule::Create({{.steps = 1, .spec = Constant()}}).ok());
}

}  // namespace
}  // namespace dcs::env
