// Copyright 2026 The DCS Authors.
#include "report/sweep_report.h"

#include <cmath>
#include <string>
#include <vector>

#include <google/protobuf/util/message_differencer.h>

#include "coordinator/iqm.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/significance.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;

struct EvalSpec {
  double combined;
  double id = 0;
  double ood_low = 0;
  double ood_high = 0;
};

// A finished run's log; best_anytime_index is the highest avg_combined's unless given (as a
// multi-stage run records only stage boundaries and the end).
v1::EvaluationLog Log(uint64_t seed, const std::vector<EvalSpec>& evaluations,
                      int best_index = -1) {
  v1::EvaluationLog log;
  log.set_seed(seed);
  log.set_complete(true);
  for (size_t i = 0; i < evaluations.size(); ++i) {
    v1::Evaluation* evaluation = log.add_evaluations();
    evaluation->set_step(1000 * static_cast<int64_t>(i + 1));
    evaluation->set_avg_combined(evaluations[i].combined);
    evaluation->mutable_id()->set_mean(evaluations[i].id);
    evaluation->mutable_ood_low()->set_mean(evaluations[i].ood_low);
    evaluation->mutable_ood_high()->set_mean(evaluations[i].ood_high);
    if (best_index < 0 && (i == 0 || evaluations[i].combined >
                                         evaluations[log.best_anytime_index()].combined)) {
      log.set_best_anytime_index(static_cast<int>(i));
    }
  }
  if (best_index >= 0) log.set_best_anytime_index(best_index);
  log.set_last(evaluations.back().combined);
  log.set_best_anytime(evaluations[log.best_anytime_index()].combined);
  return log;
}

// A trial whose runs (seeds 0, 1, ...) each have one evaluation scoring `scores[seed]`.
v1::TrialResults Trial(const std::string& condition, const std::string& family,
                       const std::string& observe, const std::vector<double>& scores) {
  v1::TrialResults trial;
  trial.set_condition(condition);
  trial.set_family(family);
  trial.set_observe(observe);
  for (size_t seed = 0; seed < scores.size(); ++seed) {
    *trial.add_runs() = Log(seed, {{.combined = scores[seed]}});
  }
  return trial;
}

v1::SweepResults Sweep(int seeds, const std::vector<v1::TrialResults>& trials) {
  v1::SweepResults results;
  results.set_sweep_id("sweep-1");
  results.set_name("families");
  results.set_seeds(seeds);
  for (const v1::TrialResults& trial : trials) *results.add_trials() = trial;
  return results;
}

ReportOptions FastOptions() {
  ReportOptions options;
  options.bootstrap_resamples = 500;
  return options;
}

TEST(SweepReportTest, IqmAndQuartilesOfHandCheckedScores) {
  // Sorted 1..8: IQM drops floor(8/4) = 2 at each end, mean(3, 4, 5, 6) = 4.5; Q1 at position
  // 7 * 0.25 = 1.75: 2 + 0.75 * (3 - 2) = 2.75; Q3 at 5.25: 6 + 0.25 * (7 - 6) = 6.25.
  const std::vector<double> scores = {8, 1, 7, 2, 6, 3, 5, 4};
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(10, {Trial("sin", "sinusoidal", "live", scores)}), ReportOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  ASSERT_EQ(report->rows_size(), 1);
  const v1::ReportCell& cell = report->rows(0).cells(0);
  EXPECT_FALSE(cell.empty());
  EXPECT_EQ(cell.runs(), 8);
  EXPECT_EQ(cell.seeds(), 10);
  EXPECT_DOUBLE_EQ(cell.summary().iqm(), 4.5);
  EXPECT_DOUBLE_EQ(cell.summary().q1(), 2.75);
  EXPECT_DOUBLE_EQ(cell.summary().q3(), 6.25);
  // The documented defaults: 10,000 resamples from seed 0 at 95%, over the seeds' scores.
  const coordinator::ConfidenceInterval expected =
      *coordinator::BootstrapIqmInterval({scores}, 0.95, 10'000, 0);
  EXPECT_EQ(cell.summary().ci_low(), expected.lo);
  EXPECT_EQ(cell.summary().ci_high(), expected.hi);
  EXPECT_LT(cell.summary().ci_low(), 4.5);
  EXPECT_GT(cell.summary().ci_high(), 4.5);
  EXPECT_EQ(report->settings().bootstrap_resamples(), 10'000);
  EXPECT_EQ(report->settings().bootstrap_seed(), 0u);
  EXPECT_EQ(report->settings().confidence(), 0.95);
  EXPECT_EQ(report->settings().checkpoint(), "last");
  EXPECT_EQ(report->settings().split(), "combined");
  ASSERT_EQ(cell.scores_size(), 8);
  EXPECT_EQ(cell.scores(3).seed(), 3u);
  EXPECT_EQ(cell.scores(3).score(), 2);
}

TEST(SweepReportTest, StaticBaselineFirstModesInSweepOrderAndEveryCellPresent) {
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(
      Sweep(3, {Trial("sin", "sinusoidal", "live", {1, 2, 3}),
                Trial("sin", "sinusoidal", "none", {1, 2, 3}),
                Trial("static", "static", "none", {1, 2, 3}),
                Trial("static", "static", "live", {}),  // no finished run yet
                Trial("cos", "cosine_annealing", "none", {4, 5, 6})}),
      FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_THAT(report->modes(), ::testing::ElementsAre("live", "none"));
  ASSERT_EQ(report->rows_size(), 3);
  EXPECT_EQ(report->rows(0).condition(), "static");
  EXPECT_TRUE(report->rows(0).baseline());
  EXPECT_EQ(report->rows(1).condition(), "sin");
  EXPECT_EQ(report->rows(1).family(), "sinusoidal");
  EXPECT_FALSE(report->rows(1).baseline());
  EXPECT_EQ(report->rows(2).condition(), "cos");
  EXPECT_EQ(report->settings().baseline(), "static");
  for (const v1::ReportRow& row : report->rows()) {
    ASSERT_EQ(row.cells_size(), 2);
    EXPECT_EQ(row.cells(0).mode(), "live");
    EXPECT_EQ(row.cells(1).mode(), "none");
  }
  // Asked for but not finished: present, empty, 0 of 3 runs.
  const v1::ReportCell& unfinished = report->rows(0).cells(0);
  EXPECT_TRUE(unfinished.empty());
  EXPECT_EQ(unfinished.runs(), 0);
  EXPECT_EQ(unfinished.seeds(), 3);
  EXPECT_FALSE(unfinished.has_summary());
  EXPECT_FALSE(unfinished.best());
  // Not in the sweep at all: present, empty, no seeds asked.
  const v1::ReportCell& absent = report->rows(2).cells(0);
  EXPECT_TRUE(absent.empty());
  EXPECT_EQ(absent.seeds(), 0);
  // Nothing to compare with where the baseline's cell is empty.
  EXPECT_FALSE(report->rows(1).cells(0).has_improvement());
  EXPECT_TRUE(report->rows(1).cells(1).has_improvement());
}

// One run with three evaluations: avg_combined 10, 30, 20; the id split 100, 5, 50.
v1::SweepResults CheckpointSweep() {
  v1::TrialResults trial;
  trial.set_condition("sin");
  trial.set_family("sinusoidal");
  trial.set_observe("live");
  *trial.add_runs() = Log(4, {{.combined = 10, .id = 100, .ood_low = 1, .ood_high = -1},
                              {.combined = 30, .id = 5, .ood_low = 2, .ood_high = -2},
                              {.combined = 20, .id = 50, .ood_low = 3, .ood_high = -3}});
  return Sweep(1, {trial});
}

v1::ReportRun ScoreRead(ReportCheckpoint checkpoint, ReportSplit split) {
  ReportOptions options = FastOptions();
  options.checkpoint = checkpoint;
  options.split = split;
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(CheckpointSweep(), options);
  EXPECT_TRUE(report.ok()) << report.status();
  if (!report.ok()) return {};
  EXPECT_EQ(report->rows(0).cells(0).summary().iqm(), report->rows(0).cells(0).scores(0).score());
  return report->rows(0).cells(0).scores(0);
}

TEST(SweepReportTest, BestCheckpointReadsTheSplitAtTheBestAvgCombinedEvaluation) {
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kLast, ReportSplit::kCombined).score(), 20);
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kBest, ReportSplit::kCombined).score(), 30);
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kLast, ReportSplit::kId).score(), 50);
  // Not the id split's own best (100, at the first evaluation): its value where avg_combined
  // is best.
  const v1::ReportRun best_id = ScoreRead(ReportCheckpoint::kBest, ReportSplit::kId);
  EXPECT_EQ(best_id.score(), 5);
  EXPECT_EQ(best_id.step(), 2000);
  EXPECT_EQ(best_id.seed(), 4u);
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kBest, ReportSplit::kOodLow).score(), 2);
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kBest, ReportSplit::kOodHigh).score(), -2);
  EXPECT_EQ(ScoreRead(ReportCheckpoint::kLast, ReportSplit::kOodHigh).score(), -3);
}

TEST(SweepReportTest, HeaderSaysWhichEvaluationAndValueAreRead) {
  ReportOptions options = FastOptions();
  options.checkpoint = ReportCheckpoint::kBest;
  options.split = ReportSplit::kId;
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(CheckpointSweep(), options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->settings().checkpoint(), "best");
  EXPECT_EQ(report->settings().split(), "id");
  EXPECT_THAT(report->settings().score_rule(), HasSubstr("the id split's mean"));
  EXPECT_THAT(report->settings().score_rule(), HasSubstr("highest avg_combined"));
  EXPECT_THAT(report->settings().score_rule(), HasSubstr("chosen by avg_combined"));
}

TEST(SweepReportTest, BestCheckpointFollowsTheRecordedIndexOfAMultiStageRun) {
  // Evaluations 70 (a stage boundary), 90 (inside a stage: not a candidate), 60 (the end): the
  // log records evaluation 0 as best-anytime, and the report reads it rather than 90.
  v1::TrialResults trial;
  trial.set_condition("stages");
  trial.set_family("multi_stage");
  trial.set_observe("live");
  *trial.add_runs() =
      Log(0, {{.combined = 70, .id = 7}, {.combined = 90, .id = 9}, {.combined = 60, .id = 6}},
          /*best_index=*/0);
  ReportOptions options = FastOptions();
  options.checkpoint = ReportCheckpoint::kBest;
  const absl::StatusOr<v1::SweepReport> combined = BuildSweepReport(Sweep(1, {trial}), options);
  ASSERT_TRUE(combined.ok()) << combined.status();
  EXPECT_EQ(combined->rows(0).cells(0).scores(0).score(), 70);
  options.split = ReportSplit::kId;
  const absl::StatusOr<v1::SweepReport> id = BuildSweepReport(Sweep(1, {trial}), options);
  ASSERT_TRUE(id.ok()) << id.status();
  EXPECT_EQ(id->rows(0).cells(0).scores(0).score(), 7);
}

TEST(SweepReportTest, MarksTheBestIqmOfEachModeAndEveryTie) {
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(3, {Trial("static", "static", "live", {1, 1, 1}),
                                 Trial("static", "static", "none", {9, 9, 9}),
                                 Trial("sin", "sinusoidal", "live", {3, 3, 3}),
                                 Trial("sin", "sinusoidal", "none", {1, 2, 3}),
                                 Trial("cos", "cosine_annealing", "live", {2, 3, 4})}),
                       FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  // live: static 1, sin 3, cos 3 (a tie); none: static 9, sin 2, cos empty.
  EXPECT_FALSE(report->rows(0).cells(0).best());
  EXPECT_TRUE(report->rows(1).cells(0).best());
  EXPECT_TRUE(report->rows(2).cells(0).best());
  EXPECT_TRUE(report->rows(0).cells(1).best());
  EXPECT_FALSE(report->rows(1).cells(1).best());
  EXPECT_FALSE(report->rows(2).cells(1).best());
}

TEST(SweepReportTest, ProbabilityOfImprovementOverTheBaselineInTheSameMode) {
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(3, {Trial("static", "static", "live", {2, 2, 2}),
                                 Trial("static", "static", "none", {1, 3, 5}),
                                 Trial("sin", "sinusoidal", "live", {1, 2, 3}),
                                 Trial("sin", "sinusoidal", "none", {3, 4})}),
                       FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_FALSE(report->rows(0).cells(0).has_improvement());  // the baseline's own row
  EXPECT_FALSE(report->rows(0).cells(1).has_improvement());
  // live: {1, 2, 3} over {2, 2, 2}: 1 loses 3 pairs, 2 ties 3 (0.5 each), 3 wins 3:
  // (0 + 1.5 + 3) / 9 = 0.5.
  const v1::Improvement& live = report->rows(1).cells(0).improvement();
  EXPECT_DOUBLE_EQ(live.probability(), 0.5);
  // none: {3, 4} over {1, 3, 5}, against the baseline's none runs, not its live ones:
  // 3 > 1, 3 = 3, 3 < 5, 4 > 1, 4 > 3, 4 < 5: (1 + 0.5 + 0 + 1 + 1 + 0) / 6 = 3.5 / 6.
  const v1::Improvement& none = report->rows(1).cells(1).improvement();
  EXPECT_DOUBLE_EQ(none.probability(), 3.5 / 6);
  for (const v1::Improvement* improvement : {&live, &none}) {
    EXPECT_LE(improvement->ci_low(), improvement->probability());
    EXPECT_GE(improvement->ci_high(), improvement->probability());
    EXPECT_GE(improvement->ci_low(), 0);
    EXPECT_LE(improvement->ci_high(), 1);
    EXPECT_LT(improvement->ci_low(), improvement->ci_high());
  }
}

// Each condition's Mann-Whitney p-value is adjusted over the comparisons of its mode: with three
// conditions, the two far from the baseline get three times their p-value (their step-down's
// maximum), and are significant, one better and one worse; the one that overlaps it is not.
TEST(SweepReportTest, SignificanceIsHolmAdjustedOverTheModesComparisons) {
  std::vector<double> baseline, above, below, overlapping;
  for (int seed = 0; seed < 10; ++seed) {
    baseline.push_back(seed);
    above.push_back(100 + seed);
    below.push_back(-100 - seed);
    overlapping.push_back(seed + 0.5);
  }
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(10, {Trial("static", "static", "live", baseline),
                                  Trial("above", "sinusoidal", "live", above),
                                  Trial("below", "random_walk", "live", below),
                                  Trial("overlapping", "levy_walk", "live", overlapping)}),
                       FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  const absl::StatusOr<MannWhitney> apart = MannWhitneyTest(above, baseline);
  const absl::StatusOr<MannWhitney> near = MannWhitneyTest(overlapping, baseline);
  ASSERT_TRUE(apart.ok() && near.ok());
  const v1::Improvement& better = report->rows(1).cells(0).improvement();
  const v1::Improvement& worse = report->rows(2).cells(0).improvement();
  const v1::Improvement& unclear = report->rows(3).cells(0).improvement();
  for (const v1::Improvement* improvement : {&better, &worse}) {
    EXPECT_EQ(improvement->p_value(), apart->p_value);
    EXPECT_EQ(improvement->holm_p_value(), 3 * apart->p_value);
    EXPECT_TRUE(improvement->significant());
  }
  EXPECT_EQ(better.probability(), 1);
  EXPECT_EQ(worse.probability(), 0);
  EXPECT_EQ(unclear.p_value(), near->p_value);
  EXPECT_EQ(unclear.holm_p_value(), near->p_value);  // the largest: adjusted by a factor of 1
  EXPECT_FALSE(unclear.significant());
  EXPECT_THAT(report->settings().significance_rule(), HasSubstr("Holm"));
}

TEST(SweepReportTest, WithoutAStaticConditionThereIsNoImprovementAndNoError) {
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(2, {Trial("sin", "sinusoidal", "live", {1, 2}),
                                 Trial("cos", "cosine_annealing", "live", {3, 4})}),
                       FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->settings().baseline(), "");
  EXPECT_EQ(report->rows(0).condition(), "sin");
  for (const v1::ReportRow& row : report->rows()) {
    EXPECT_FALSE(row.baseline());
    EXPECT_FALSE(row.cells(0).has_improvement());
  }
}

TEST(SweepReportTest, ANamedBaselineComesFirstAndAnUnknownOneIsAnError) {
  const v1::SweepResults sweep = Sweep(2, {Trial("static", "static", "live", {1, 2}),
                                           Trial("sin", "sinusoidal", "live", {3, 4})});
  ReportOptions options = FastOptions();
  options.baseline = "sin";
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(sweep, options);
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->rows(0).condition(), "sin");
  EXPECT_EQ(report->rows(1).condition(), "static");
  EXPECT_DOUBLE_EQ(report->rows(1).cells(0).improvement().probability(), 0);
  options.baseline = "sine";
  const absl::StatusOr<v1::SweepReport> unknown = BuildSweepReport(sweep, options);
  EXPECT_EQ(unknown.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(unknown.status().message(), HasSubstr("sine"));
  EXPECT_THAT(unknown.status().message(), HasSubstr("static, sin"));
}

TEST(SweepReportTest, TheSameInputGivesTheSameReportAndAnotherSeedOtherIntervals) {
  const v1::SweepResults sweep =
      Sweep(10, {Trial("static", "static", "live", {5, 1, 4, 2, 8, 9, 3, 7, 6, 0}),
                 Trial("sin", "sinusoidal", "live", {3, 6, 9, 2, 5, 8, 1, 4, 7, 10})});
  ReportOptions options = FastOptions();
  const absl::StatusOr<v1::SweepReport> first = BuildSweepReport(sweep, options);
  const absl::StatusOr<v1::SweepReport> second = BuildSweepReport(sweep, options);
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_EQ(first->SerializeAsString(), second->SerializeAsString());
  options.bootstrap_seed = 1;
  const absl::StatusOr<v1::SweepReport> other = BuildSweepReport(sweep, options);
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(other->settings().bootstrap_seed(), 1u);
  const v1::ReportCell& a = first->rows(1).cells(0);
  const v1::ReportCell& b = other->rows(1).cells(0);
  EXPECT_EQ(a.summary().iqm(), b.summary().iqm());
  EXPECT_TRUE(a.summary().ci_low() != b.summary().ci_low() ||
              a.summary().ci_high() != b.summary().ci_high());
  EXPECT_EQ(a.improvement().probability(), b.improvement().probability());
  EXPECT_TRUE(a.improvement().ci_low() != b.improvement().ci_low() ||
              a.improvement().ci_high() != b.improvement().ci_high());
}

TEST(SweepReportTest, ANanScoreIsAnErrorNamingTheTrialAndSeed) {
  v1::TrialResults trial = Trial("sin", "sinusoidal", "live", {1, 2, 3});
  trial.mutable_runs(2)->set_seed(7);
  trial.mutable_runs(2)->mutable_evaluations(0)->set_avg_combined(std::nan(""));
  const absl::StatusOr<v1::SweepReport> report =
      BuildSweepReport(Sweep(3, {trial}), FastOptions());
  EXPECT_EQ(report.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(report.status().message(), HasSubstr("sin (live)"));
  EXPECT_THAT(report.status().message(), HasSubstr("seed 7"));
  EXPECT_THAT(report.status().message(), HasSubstr("nan"));
}

// `trial` with coverage of a 100-cell projection "state" on its runs: run i visits
// `first[i]` cells in steps (0, 50] and 5 cells in (50, 100], `added[i]` of them new.
v1::TrialResults WithCoverage(v1::TrialResults trial, const std::vector<int>& first,
                              const std::vector<int>& added) {
  for (int i = 0; i < trial.runs_size(); ++i) {
    v1::ProjectionCoverage& coverage = *trial.mutable_runs(i)->add_coverage();
    coverage.set_projection("state");
    coverage.set_cells(100);
    v1::CoverageWindow& early = *coverage.add_windows();
    early.set_end_step(50);
    early.set_visited(first[i]);
    early.set_new_cells(first[i]);
    v1::CoverageWindow& late = *coverage.add_windows();
    late.set_start_step(50);
    late.set_end_step(100);
    late.set_visited(5);
    late.set_new_cells(added[i]);
  }
  return trial;
}

TEST(SweepReportTest, CoverageSectionsCompareConditionsByAnovaAndCorrelateWithTheScore) {
  v1::TrialResults sin = WithCoverage(Trial("sin", "sinusoidal", "none", {300, 320, 340}),
                                      {18, 20, 22}, {2, 2, 2});
  *sin.add_runs() = Log(3, {{.combined = 500}});  // counted no coverage: left out
  const v1::SweepResults results =
      Sweep(4, {WithCoverage(Trial("static", "static", "none", {100, 120, 140}), {9, 11, 13},
                             {1, 1, 1}),
                sin});
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(results, FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  ASSERT_EQ(report->coverage_size(), 1);
  const v1::CoverageSection& section = report->coverage(0);
  EXPECT_EQ(section.projection(), "state");
  EXPECT_EQ(section.cells(), 100);
  EXPECT_THAT(section.window_ends(), ::testing::ElementsAre(50, 100));
  ASSERT_EQ(section.rows_size(), 2);
  EXPECT_EQ(section.rows(0).condition(), "static");
  EXPECT_THAT(section.rows(0).runs(), ::testing::ElementsAre(10, 12, 14));
  EXPECT_DOUBLE_EQ(section.rows(0).mean(), 12);
  EXPECT_DOUBLE_EQ(section.rows(0).sem(), 2 / std::sqrt(3.0));
  EXPECT_THAT(section.rows(0).window_means(), ::testing::ElementsAre(11, 5));
  EXPECT_THAT(section.rows(1).runs(), ::testing::ElementsAre(20, 22, 24));
  ASSERT_EQ(section.tests_size(), 1);
  const v1::CoverageTest& test = section.tests(0);
  EXPECT_EQ(test.mode(), "none");
  // SSB = 3 (12 - 17)^2 + 3 (22 - 17)^2 = 150 on 1 df; SSW = 8 + 8 = 16 on 4: F = 37.5.
  EXPECT_DOUBLE_EQ(test.anova().f(), 37.5);
  EXPECT_EQ(test.anova().df_between(), 1);
  EXPECT_EQ(test.anova().df_within(), 4);
  EXPECT_LT(test.anova().p_value(), 0.01);
  // Coverage rises with the score run for run.
  EXPECT_EQ(test.correlation().runs(), 6);
  EXPECT_GT(test.correlation().r(), 0.9);
  EXPECT_TRUE(test.note().empty());
}

TEST(SweepReportTest, CoverageOfOneConditionHasNoAnovaAndSaysWhy) {
  const absl::StatusOr<v1::SweepReport> report = BuildSweepReport(
      Sweep(2, {WithCoverage(Trial("static", "static", "none", {1, 2}), {9, 11}, {1, 1})}),
      FastOptions());
  ASSERT_TRUE(report.ok()) << report.status();
  const v1::CoverageTest& test = report->coverage(0).tests(0);
  EXPECT_FALSE(test.has_anova());
  EXPECT_FALSE(test.has_correlation());
  EXPECT_THAT(test.note(), HasSubstr("no ANOVA: a one-way ANOVA needs at least two groups"));
  EXPECT_THAT(test.note(), HasSubstr("no correlation: a correlation's test needs at least three"));
  // Without coverage in any run there is no section.
  EXPECT_EQ(BuildSweepReport(Sweep(2, {Trial("static", "static", "none", {1, 2})}), FastOptions())
                ->coverage_size(),
            0);
}

TEST(SweepReportTest, RefusesBadRunsAndBadSweeps) {
  const auto code = [](const v1::SweepResults& sweep, const ReportOptions& options) {
    return BuildSweepReport(sweep, options).status().code();
  };
  const ReportOptions options = FastOptions();
  constexpr absl::StatusCode kInvalid = absl::StatusCode::kInvalidArgument;

  v1::TrialResults unfinished = Trial("sin", "sinusoidal", "live", {1, 2});
  unfinished.mutable_runs(1)->set_complete(false);
  EXPECT_EQ(code(Sweep(2, {unfinished}), options), kInvalid);

  v1::TrialResults no_evaluations = Trial("sin", "sinusoidal", "live", {1, 2});
  no_evaluations.mutable_runs(0)->clear_evaluations();
  EXPECT_EQ(code(Sweep(2, {no_evaluations}), options), kInvalid);

  v1::TrialResults twice = Trial("sin", "sinusoidal", "live", {1, 2});
  twice.mutable_runs(1)->set_seed(0);
  EXPECT_EQ(code(Sweep(2, {twice}), options), kInvalid);

  const v1::TrialResults trial = Trial("sin", "sinusoidal", "live", {1, 2});
  EXPECT_EQ(code(Sweep(2, {trial, trial}), options), kInvalid);
  EXPECT_EQ(code(Sweep(2, {trial, Trial("sin", "random_walk", "none", {1})}), options), kInvalid);
  EXPECT_EQ(code(Sweep(2, {Trial("", "static", "live", {1})}), options), kInvalid);
  EXPECT_EQ(code(Sweep(2, {Trial("static", "static", "", {1})}), options), kInvalid);

  ReportOptions best = options;
  best.checkpoint = ReportCheckpoint::kBest;
  v1::TrialResults out_of_range = Trial("sin", "sinusoidal", "live", {1, 2});
  out_of_range.mutable_runs(0)->set_best_anytime_index(1);
  EXPECT_EQ(code(Sweep(2, {out_of_range}), best), kInvalid);
  v1::TrialResults disagrees = Trial("sin", "sinusoidal", "live", {1, 2});
  disagrees.mutable_runs(0)->set_best_anytime(5);
  EXPECT_EQ(code(Sweep(2, {disagrees}), best), kInvalid);
  EXPECT_EQ(code(Sweep(2, {out_of_range}), options), absl::StatusCode::kOk);  // last: not read

  ReportOptions id = options;
  id.split = ReportSplit::kId;
  v1::TrialResults no_split = Trial("sin", "sinusoidal", "live", {1, 2});
  no_split.mutable_runs(0)->mutable_evaluations(0)->clear_id();
  EXPECT_EQ(code(Sweep(2, {no_split}), id), kInvalid);
  EXPECT_EQ(code(Sweep(2, {no_split}), options), absl::StatusCode::kOk);  // combined: not read

  ReportOptions bad = options;
  bad.bootstrap_resamples = 0;
  EXPECT_EQ(code(Sweep(2, {trial}), bad), kInvalid);
  bad = options;
  bad.confidence = 1;
  EXPECT_EQ(code(Sweep(2, {trial}), bad), kInvalid);
}

}  // namespace
}  // namespace dcs::report
