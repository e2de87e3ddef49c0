// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_results.h"

#include <filesystem>
#include <string>
#include <vector>

#include "coordinator/run_files.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::HasSubstr;

// A finished run's log: one evaluation of two contexts, three episodes each.
v1::EvaluationLog Log(uint64_t seed, double score) {
  v1::EvaluationLog log;
  log.set_env("cartpole");
  log.set_seed(seed);
  log.set_complete(true);
  log.set_last(score);
  log.set_best_anytime(score);
  v1::Evaluation& evaluation = *log.add_evaluations();
  evaluation.set_step(100);
  evaluation.set_avg_combined(score);
  for (v1::Split split : {v1::SPLIT_ID, v1::SPLIT_OOD_HIGH}) {
    v1::ContextEvaluation& context = *evaluation.add_contexts();
    context.set_split(split);
    context.set_mean(score);
    for (int episode = 0; episode < 3; ++episode) context.add_returns(score);
  }
  return log;
}

class SweepResultsTest : public testing::TempDirTest {
 protected:
  RunRecord Completed(int number, int trial, uint64_t seed) {
    RunRecord run{.id = "run-" + std::to_string(number), .state = RunState::kCompleted};
    run.trial = trial;
    run.submission.seed = seed;
    const std::string run_dir = RunDirectory(dir().string(), run.id);
    std::filesystem::create_directories(run_dir);
    EXPECT_TRUE(run::WriteEvaluationLog(run_dir, Log(seed, 100 + seed)).ok());
    return run;
  }
};

TEST_F(SweepResultsTest, EachTrialGetsItsCompletedRunsInSeedOrderWithoutReturns) {
  const SweepRecord sweep{.id = "sweep-1", .name = "grid", .seeds = 2,
                          .trials = {{.condition = "static", .family = "static", .observe = "none"},
                                     {.condition = "sine", .family = "sinusoidal",
                                      .observe = "none"}}};
  std::vector<RunRecord> runs = {Completed(1, 1, 7), Completed(2, 1, 3), Completed(3, 0, 5)};
  runs.push_back({.id = "run-4", .state = RunState::kRunning});  // not read
  runs.back().trial = 0;
  CompletedRunLogs logs(dir().string());
  absl::StatusOr<v1::SweepResults> results = CollectSweepResults(sweep, runs, logs);
  ASSERT_TRUE(results.ok()) << results.status();
  ASSERT_EQ(results->trials_size(), 2);
  EXPECT_EQ(results->trials(0).condition(), "static");
  ASSERT_EQ(results->trials(0).runs_size(), 1);
  ASSERT_EQ(results->trials(1).runs_size(), 2);
  EXPECT_EQ(results->trials(1).runs(0).seed(), 3u);
  EXPECT_EQ(results->trials(1).runs(1).seed(), 7u);
  EXPECT_EQ(results->trials(1).runs(1).evaluations(0).contexts(1).mean(), 107);
  EXPECT_EQ(results->trials(1).runs(1).evaluations(0).contexts(1).returns_size(), 0);
}

TEST_F(SweepResultsTest, ALogIsReadOnceAndAMissingOneIsDataLoss) {
  const RunRecord run = Completed(1, 0, 2);
  CompletedRunLogs logs(dir().string());
  ASSERT_TRUE(logs.Get(run).ok());
  // Kept: the file is not read again.
  std::filesystem::remove_all(RunDirectory(dir().string(), run.id));
  absl::StatusOr<v1::EvaluationLog> again = logs.Get(run);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(again->last(), 102);
  const absl::Status missing = logs.Get({.id = "run-9", .state = RunState::kCompleted}).status();
  EXPECT_EQ(missing.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(missing.message(), HasSubstr("run-9"));
}

}  // namespace
}  // namespace dcs::coordinator
