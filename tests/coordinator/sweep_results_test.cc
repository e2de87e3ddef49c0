// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_results.h"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "coordinator/run_files.h"
#include "report/sweep_report.h"
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
  absl::StatusOr<v1::SweepResults> results = CollectSweepResults(sweep, runs, logs, /*scores_only=*/false);
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

// A run of evaluations scoring `scores` at steps 10, 20, ..., its best-anytime the highest, each
// with a context per split.
v1::EvaluationLog Scored(uint64_t seed, const std::vector<double>& scores) {
  v1::EvaluationLog log;
  log.set_seed(seed);
  log.set_complete(true);
  for (size_t i = 0; i < scores.size(); ++i) {
    v1::Evaluation& evaluation = *log.add_evaluations();
    evaluation.set_step(10 * static_cast<int64_t>(i + 1));
    evaluation.set_avg_combined(scores[i]);
    evaluation.mutable_id()->set_mean(scores[i] + 1);
    evaluation.mutable_ood_low()->set_mean(scores[i] - 1);
    evaluation.mutable_ood_high()->set_mean(scores[i] / 2);
    evaluation.add_contexts()->set_mean(scores[i]);
    if (scores[i] > scores[log.best_anytime_index()]) log.set_best_anytime_index(i);
  }
  log.set_last(scores.back());
  log.set_best_anytime(scores[log.best_anytime_index()]);
  log.add_coverage()->set_projection("state");
  return log;
}

TEST(KeepScoresOnlyTest, KeepsTheLastAndTheBestEvaluationWithoutContexts) {
  v1::EvaluationLog log = Scored(0, {1, 5, 3, 2});
  KeepScoresOnly(log);
  ASSERT_EQ(log.evaluations_size(), 2);
  EXPECT_EQ(log.evaluations(0).step(), 20);
  EXPECT_EQ(log.evaluations(1).step(), 40);
  EXPECT_EQ(log.best_anytime_index(), 0);
  EXPECT_EQ(log.evaluations(0).contexts_size(), 0);
  EXPECT_EQ(log.coverage_size(), 1);
  v1::EvaluationLog best_last = Scored(0, {1, 2, 3});
  KeepScoresOnly(best_last);
  ASSERT_EQ(best_last.evaluations_size(), 1);
  EXPECT_EQ(best_last.best_anytime_index(), 0);
}

TEST(KeepScoresOnlyTest, AReportOfCutLogsIsTheReportOfWholeOnes) {
  v1::SweepResults whole;
  whole.set_seeds(3);
  const std::vector<std::vector<double>> runs = {{1, 5, 3}, {2, 2, 9}, {7, 1, 1}, {4, 6, 5}};
  for (const auto& [condition, offset] : {std::pair("static", 0.0), std::pair("sin", 1.0)}) {
    v1::TrialResults& trial = *whole.add_trials();
    trial.set_condition(condition);
    trial.set_family(condition);
    trial.set_observe("none");
    for (size_t seed = 0; seed < runs.size(); ++seed) {
      std::vector<double> scores = runs[seed];
      for (double& score : scores) score += offset;
      *trial.add_runs() = Scored(seed, scores);
    }
  }
  v1::SweepResults cut = whole;
  for (v1::TrialResults& trial : *cut.mutable_trials()) {
    for (v1::EvaluationLog& log : *trial.mutable_runs()) KeepScoresOnly(log);
  }
  for (report::ReportCheckpoint checkpoint :
       {report::ReportCheckpoint::kLast, report::ReportCheckpoint::kBest}) {
    for (report::ReportSplit split : {report::ReportSplit::kCombined, report::ReportSplit::kId,
                                      report::ReportSplit::kOodLow, report::ReportSplit::kOodHigh}) {
      report::ReportOptions options{
          .checkpoint = checkpoint, .split = split, .bootstrap_resamples = 50};
      absl::StatusOr<v1::SweepReport> from_whole = report::BuildSweepReport(whole, options);
      absl::StatusOr<v1::SweepReport> from_cut = report::BuildSweepReport(cut, options);
      ASSERT_TRUE(from_whole.ok()) << from_whole.status();
      ASSERT_TRUE(from_cut.ok()) << from_cut.status();
      EXPECT_EQ(from_cut->SerializeAsString(), from_whole->SerializeAsString());
    }
  }
}

}  // namespace
}  // namespace dcs::coordinator
