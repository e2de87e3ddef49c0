// Copyright 2026 The DCS Authors.
//
// A study sweep's report (report/study_report.h) from hand-made results: the ranking, the
// best trials' stage modes, the rank correlations between search and retrain, and the retrain
// tables; and its figures (report/study_figures.h).

#include "report/study_report.h"

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/study_figures.h"

namespace dcs::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kSpec[] = R"(name: search
seeds: 2
observe: [live]
env: cartpole
evaluation: {contexts: {id: [0.5]}}
conditions:
  - name: base
    stages:
      - {steps: 1000, schedule: {family: constant}}
      - {steps: 1000, schedule: {family: constant}}
study:
  trials: 6
  retrain: {top_k: 5, seeds: 2}
  space:
    parameters:
      - {name: "stages[0].schedule.family", type: categorical, choices: [constant, sinusoidal]}
      - {name: "stages[0].schedule.period", type: int, low: 25, high: 500,
         when: {"stages[0].schedule.family": sinusoidal}}
      - {name: "stages[1].schedule.family", type: categorical,
         choices: [constant, cosine_annealing]}
      - {name: "stages[1].schedule.T_0", type: int, low: 25, high: 500,
         when: {"stages[1].schedule.family": cosine_annealing}}
)";

v1::EvaluationLog Log(uint64_t seed, double best, double last) {
  v1::EvaluationLog log;
  log.set_seed(seed);
  // The best at the stage boundary, the last at the end.
  v1::Evaluation* boundary = log.add_evaluations();
  boundary->set_step(1000);
  boundary->set_avg_combined(best);
  v1::Evaluation* end = log.add_evaluations();
  end->set_step(2000);
  end->set_avg_combined(last);
  log.set_last(last);
  log.set_best_anytime(best);
  log.set_best_anytime_index(0);
  log.set_complete(true);
  return log;
}

// Trials 0-4 complete with objectives 50, 40, 30, 20, 10 (trial n: 50 - 10n), trial 5 pruned
// at 5; trial n takes sinusoidal in stage 1 for even n, cosine annealing in stage 2 for n < 2.
// The five are retrained with objectives that rank them 1, 3, 2, 5, 4.
struct Study {
  v1::SweepResults results;
  std::vector<coordinator::StudyTrial> trials;
};

Study MakeStudy() {
  Study study;
  study.results.set_sweep_id("sweep-1");
  study.results.set_name("search");
  study.results.set_seeds(2);
  study.results.set_spec(kSpec);
  study.results.set_study_id("study-1");
  const double retrain[] = {45, 25, 35, 5, 15};
  for (int n = 0; n < 6; ++n) {
    coordinator::StudyTrial trial{
        .number = n,
        .state = n < 5 ? coordinator::TrialState::kComplete : coordinator::TrialState::kPruned,
        .value = 50.0 - 10 * n};
    trial.values["stages[0].schedule.family"] = n % 2 == 0 ? 1 : 0;
    if (n % 2 == 0) trial.values["stages[0].schedule.period"] = 100 + n;
    trial.values["stages[1].schedule.family"] = n < 2 ? 1 : 0;
    if (n < 2) trial.values["stages[1].schedule.T_0"] = 250;
    if (n == 5) trial.reported[1000] = 5;
    study.trials.push_back(trial);
    v1::TrialResults& search = *study.results.add_trials();
    search.set_condition(absl::StrCat("T00", n));
    search.set_family("multi_stage");
    search.set_observe("live");
    search.set_study_trial(n);
  }
  for (int n = 0; n < 5; ++n) {
    v1::TrialResults& again = *study.results.add_trials();
    again.set_condition(absl::StrCat("T00", n, " retrain"));
    again.set_family("multi_stage");
    again.set_observe("live");
    again.set_study_trial(n);
    again.set_retrain(true);
    // Seeds' best-anytime retrain[n] ± 1 (mean retrain[n]); last 10 below.
    *again.add_runs() = Log(2, retrain[n] - 1, retrain[n] - 11);
    *again.add_runs() = Log(3, retrain[n] + 1, retrain[n] - 9);
  }
  return study;
}

TEST(StudyReportTest, RanksTheTrialsAndComparesTheRetrain) {
  const Study study = MakeStudy();
  absl::StatusOr<v1::StudyReport> report =
      BuildStudyReport(study.results, study.trials, 3, {.bootstrap_resamples = 100});
  ASSERT_TRUE(report.ok()) << report.status();
  EXPECT_EQ(report->objective(), "best_anytime");
  EXPECT_EQ(report->retrain_seeds(), 2);
  ASSERT_EQ(report->trials_size(), 6);
  std::vector<int64_t> order;
  for (const auto& trial : report->trials()) order.push_back(trial.trial());
  EXPECT_THAT(order, ElementsAre(0, 1, 2, 3, 4, 5));
  const v1::StudyReport::Trial& first = report->trials(0);
  EXPECT_EQ(first.rank(), 1);
  EXPECT_EQ(first.value(), 50);
  EXPECT_THAT(first.stage_modes(), ElementsAre("sinusoidal", "cosine_annealing"));
  EXPECT_THAT(first.parameters(), ElementsAre("s0.period=100", "s1.T_0=250"));
  EXPECT_EQ(first.retrain_value(), 45);
  std::vector<int> retrain_ranks;
  for (const auto& trial : report->trials()) retrain_ranks.push_back(trial.retrain_rank());
  EXPECT_THAT(retrain_ranks, ElementsAre(1, 3, 2, 5, 4, 0));
  const v1::StudyReport::Trial& pruned = report->trials(5);
  EXPECT_EQ(pruned.state(), "pruned");
  EXPECT_EQ(pruned.rank(), 0);
  EXPECT_EQ(pruned.value(), 5);

  // The best 3 (trials 0, 1, 2): stage 1 sinusoidal, constant, sinusoidal; stage 2 cosine
  // annealing twice, constant once. Modes: every stage's, in order of first appearance.
  EXPECT_EQ(report->top(), 3);
  EXPECT_THAT(report->modes(), ElementsAre("constant", "sinusoidal", "cosine_annealing"));
  EXPECT_THAT(report->mode_counts(), ElementsAre(1, 2, 0, 1, 0, 2));

  // Ranks 1-5 against 1, 3, 2, 5, 4: rho = 1 - 6 * 4 / (5 * 24) = 0.8, p (t with 3 degrees of
  // freedom, as scipy.stats.spearmanr) = 0.1041; tau-b = (8 - 2) / 10.
  EXPECT_EQ(report->rank_pairs(), 5);
  EXPECT_NEAR(report->spearman_rho(), 0.8, 1e-12);
  EXPECT_NEAR(report->spearman_p(), 0.1041, 1e-4);
  EXPECT_NEAR(report->kendall_tau(), 0.6, 1e-12);

  // The retrain tables: a row per retrained trial, named by its trial.
  ASSERT_EQ(report->retrain_best().rows_size(), 5);
  EXPECT_EQ(report->retrain_best().rows(0).condition(), "T000");
  EXPECT_EQ(report->retrain_best().rows(0).cells(0).summary().iqm(), 45);
  EXPECT_EQ(report->retrain_last().rows(0).cells(0).summary().iqm(), 35);

  const std::string table = FormatStudyReport(*report, ReportFormat::kTable, 2);
  EXPECT_THAT(table, HasSubstr("Search rank vs retrain rank: Spearman rho = 0.80 (p = 0.1), "
                               "Kendall tau-b = 0.60"));
  EXPECT_THAT(table, HasSubstr("sinusoidal > cosine_annealing"));
  EXPECT_THAT(table, HasSubstr("Stage modes of the best 3 trials"));
  EXPECT_THAT(FormatStudyReport(*report, ReportFormat::kCsv, 2),
              HasSubstr("1,T000,complete,50.0,sinusoidal;cosine_annealing,"
                        "s0.period=100;s1.T_0=250,45.0,1\n"));
  EXPECT_THAT(FormatStudyReport(*report, ReportFormat::kLatex, 2), HasSubstr("\\toprule"));
}

TEST(StudyReportTest, APlainSweepHasNoStudyReport) {
  Study study = MakeStudy();
  study.results.clear_study_id();
  EXPECT_EQ(BuildStudyReport(study.results, study.trials, 3, {}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(StudyReportTest, FiguresDrawTheModesAndTheRankShift) {
  const Study study = MakeStudy();
  absl::StatusOr<v1::StudyReport> report =
      BuildStudyReport(study.results, study.trials, 3, {.bootstrap_resamples = 100});
  ASSERT_TRUE(report.ok()) << report.status();
  absl::StatusOr<GnuplotFigure> modes = StudyStageModesFigure(*report);
  ASSERT_TRUE(modes.ok()) << modes.status();
  EXPECT_EQ(modes->name, "study-1_stage_modes");
  EXPECT_THAT(modes->data[0].csv, HasSubstr("0,1,2,16777215,2,1,sinusoidal\n"));
  absl::StatusOr<GnuplotFigure> shift = StudyRankShiftFigure(*report);
  ASSERT_TRUE(shift.ok()) << shift.status();
  EXPECT_THAT(shift->script, HasSubstr("T003"));

  // Without retrained trials there is no rank shift to draw.
  v1::StudyReport searched = *report;
  for (auto& trial : *searched.mutable_trials()) trial.set_retrain_rank(0);
  EXPECT_EQ(StudyRankShiftFigure(searched).status().code(), absl::StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace dcs::report
