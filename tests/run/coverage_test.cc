// Copyright 2026 The DCS Authors.
#include "run/coverage.h"

#include <limits>
#include <string>
#include <vector>

#include "absl/strings/str_replace.h"
#include "env/bipedal_walker.h"
#include "env/car_racing.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_checkpoint.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

// One dimension of [0, 4) in 4 bins: an input's value is its cell.
const std::vector<env::StateProjection> kLine = {
    {.name = "line", .dims = {0}, .bins = 4, .low = {0}, .high = {4}}};

// A rollout of `steps` steps of `envs` slots whose inputs are {cell, context} in time-major order.
actor::Rollout RolloutOf(int steps, int envs, const std::vector<float>& cells) {
  actor::Rollout rollout{.num_steps = steps, .num_envs = envs};
  for (float cell : cells) rollout.inputs.insert(rollout.inputs.end(), {cell + 0.5f, 9.0f});
  return rollout;
}

struct Window {
  int64_t start, end, visited, new_cells;
  bool operator==(const Window&) const = default;
};

std::vector<Window> Windows(const std::vector<ProjectionCounts>& counts, int64_t window,
                            int64_t timesteps) {
  v1::EvaluationLog log;
  AppendCoverage(counts, window, timesteps, log);
  std::vector<Window> windows;
  for (const v1::CoverageWindow& w : log.coverage(0).windows()) {
    windows.push_back({w.start_step(), w.end_step(), w.visited(), w.new_cells()});
  }
  return windows;
}

TEST(CoverageTest, CountsCellsPerWindowOfRunStepsAndNewOnes) {
  std::vector<ProjectionCounts> counts = NewCoverage(kLine);
  // Window of 4 steps; 2 slots, 3 steps a rollout: run steps 1-6, then 7-12.
  RecordCoverage(kLine, 4, RolloutOf(3, 2, {0, 1, 1, 1, 2, 2}), 0, counts);
  EXPECT_EQ(Windows(counts, 4, 6), (std::vector<Window>{{0, 4, 2, 2}, {4, 6, 1, 1}}));
  RecordCoverage(kLine, 4, RolloutOf(3, 2, {3, 0, 0, 0, 2, 2}), 6, counts);
  // Steps 5-8: cells 2, 2, 3, 0 (3 new); 9-12: 0, 0, 2, 2 (none new).
  EXPECT_EQ(Windows(counts, 4, 12),
            (std::vector<Window>{{0, 4, 2, 2}, {4, 8, 3, 2}, {8, 12, 2, 0}}));
  const v1::EvaluationLog log = [&] {
    v1::EvaluationLog l;
    AppendCoverage(counts, 4, 12, l);
    return l;
  }();
  EXPECT_EQ(log.coverage(0).projection(), "line");
  EXPECT_EQ(log.coverage(0).cells(), 4);
}

TEST(CoverageTest, NoWindowBeforeTheFirstStep) {
  EXPECT_TRUE(Windows(NewCoverage(kLine), 4, 0).empty());
}

TEST(CoverageTest, CountsRoundTripThroughTheRunStateExactly) {
  std::vector<ProjectionCounts> counts = NewCoverage(env::CartPole::CoverageProjections());
  actor::Rollout rollout{.num_steps = 5, .num_envs = 1};
  for (int t = 0; t < 5; ++t) rollout.inputs.insert(rollout.inputs.end(), {0.3f * t, -1, 0, 2});
  RecordCoverage(env::CartPole::CoverageProjections(), 3, rollout, 0, counts);
  RunState state{.coverage = counts};
  absl::StatusOr<RunState> read = DecodeRunState(EncodeRunState(state), "run.yaml");
  ASSERT_TRUE(read.ok()) << read.status();
  ASSERT_EQ(read->coverage.size(), 1u);
  const ProjectionCounts& back = read->coverage[0];
  EXPECT_EQ(back.projection, "state");
  EXPECT_EQ(back.cells, 20'736);
  EXPECT_EQ(back.window, counts[0].window);
  EXPECT_EQ(back.window_new, counts[0].window_new);
  EXPECT_EQ(back.seen, counts[0].seen);
  EXPECT_EQ(back.window_seen, counts[0].window_seen);
  EXPECT_EQ(Windows(read->coverage, 3, 5), Windows(counts, 3, 5));
  // Cart positions 0, 0.3 | 0.6 | 0.9, 1.2 fall in bins 6 | 7 | 8 of 12 over [-2.5, 2.5].
  EXPECT_EQ(Windows(counts, 3, 5), (std::vector<Window>{{0, 3, 2, 2}, {3, 5, 1, 1}}));
}

TEST(CoverageTest, ACheckpointWhoseBitsDoNotFitItsCellsIsDataLoss) {
  RunState state{.coverage = NewCoverage(kLine)};
  const std::string text = EncodeRunState(state);
  const std::string wrong = absl::StrReplaceAll(text, {{"cells: 4", "cells: 4000"}});
  ASSERT_NE(wrong, text);
  absl::StatusOr<RunState> read = DecodeRunState(wrong, "run.yaml");
  EXPECT_EQ(read.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(read.status().message(), HasSubstr("run.yaml: the coverage of projection 'line'"));
}

// Issue 14 (found by tests/fuzz/checkpoint_fuzzer): a checkpoint's cell count near the largest
// int64_t overflowed the rounding up of BitsetWords (UBSan: signed integer overflow), where it
// must be a clean DATA_LOSS.
TEST(CoverageTest, BitsetWordsOfAnyCountDoesNotOverflow) {
  EXPECT_EQ(BitsetWords(0), 0u);
  EXPECT_EQ(BitsetWords(1), 1u);
  EXPECT_EQ(BitsetWords(64), 1u);
  EXPECT_EQ(BitsetWords(65), 2u);
  EXPECT_EQ(BitsetWords(-5), 0u);
  EXPECT_EQ(BitsetWords(std::numeric_limits<int64_t>::max()), size_t{1} << 57);
}

TEST(CoverageTest, ACheckpointWithTheLargestCellCountIsDataLoss) {
  RunState state{.coverage = NewCoverage(kLine)};
  const std::string text = EncodeRunState(state);
  const std::string wrong =
      absl::StrReplaceAll(text, {{"cells: 4", "cells: 9223372036854775807"}});
  ASSERT_NE(wrong, text);
  absl::StatusOr<RunState> read = DecodeRunState(wrong, "run.yaml");
  EXPECT_EQ(read.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(read.status().message(), HasSubstr("does not hold its 9223372036854775807 cells"));
}

TEST(CoverageTest, SelectsProjectionsByNameOrAll) {
  const std::vector<env::StateProjection>& walker =
      EnvironmentProjections<env::BipedalWalker>();
  absl::StatusOr<std::vector<env::StateProjection>> all = SelectProjections({}, walker);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->size(), 4u);
  absl::StatusOr<std::vector<env::StateProjection>> two =
      SelectProjections({.projections = {"posture", "inter_leg"}}, walker);
  ASSERT_TRUE(two.ok());
  EXPECT_EQ((*two)[0].name, "posture");
  EXPECT_THAT(SelectProjections({.projections = {"legs"}}, walker).status().message(),
              HasSubstr("unknown projection 'legs' (the environment has: inter_leg, joints, "
                        "posture, leg1_phase)"));
  EXPECT_THAT(SelectProjections({.projections = {"joints", "joints"}}, walker).status().message(),
              HasSubstr("'joints' is named twice"));
  EXPECT_THAT(SelectProjections({}, EnvironmentProjections<env::CarRacing>()).status().message(),
              HasSubstr("observations are images"));
}

}  // namespace
}  // namespace dcs::run
