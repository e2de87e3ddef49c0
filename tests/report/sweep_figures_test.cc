// Copyright 2026 The DCS Authors.
#include "report/sweep_figures.h"

#include <string>
#include <tuple>
#include <vector>

#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsSupersetOf;
using ::testing::Not;

std::vector<std::string> Lines(const std::string& text) {
  return absl::StrSplit(text, '\n', absl::SkipEmpty());
}

// A completed run of seed `seed`: avg_combined `curve[i]` at step 1000 i; at the last
// evaluation, contexts ID 0.4 and 0.6, OOD-low 0.1, OOD-high 0.9 (in that order) with mean
// returns 100, 200, 10 and 50, plus the seed.
v1::EvaluationLog MakeRun(int seed, const std::vector<double>& curve) {
  v1::EvaluationLog log;
  log.set_seed(seed);
  for (size_t i = 0; i < curve.size(); ++i) {
    v1::Evaluation& evaluation = *log.add_evaluations();
    evaluation.set_step(1000 * static_cast<int64_t>(i));
    evaluation.set_avg_combined(curve[i]);
  }
  for (const auto& [split, value, mean] :
       std::vector<std::tuple<v1::Split, double, double>>{{v1::SPLIT_ID, 0.4, 100},
                                                          {v1::SPLIT_ID, 0.6, 200},
                                                          {v1::SPLIT_OOD_LOW, 0.1, 10},
                                                          {v1::SPLIT_OOD_HIGH, 0.9, 50}}) {
    v1::ContextEvaluation& context = *log.mutable_evaluations()->rbegin()->add_contexts();
    context.set_split(split);
    context.set_value(value);
    context.set_mean(mean + seed);
  }
  log.set_last(curve.back());
  log.set_complete(true);
  return log;
}

// A trial with `runs` runs whose final avg_combined is `last` + seed (seeds 0, 1, ...): IQM
// last + 1.5 over four runs, Q1 last + 0.75, Q3 last + 2.25.
void AddTrial(v1::SweepResults& results, const std::string& condition, const std::string& family,
              const std::string& observe, double last, int runs = 4) {
  v1::TrialResults& trial = *results.add_trials();
  trial.set_condition(condition);
  trial.set_family(family);
  trial.set_observe(observe);
  for (int seed = 0; seed < runs; ++seed) {
    *trial.add_runs() = MakeRun(seed, {0, last / 2 + seed, last + seed});
  }
}

// Static, two sinusoidal conditions and a random walk, observing none and live; sin_big has no
// completed run in live.
v1::SweepResults Results() {
  v1::SweepResults results;
  results.set_sweep_id("sweep-7");
  results.set_name("demo");
  results.set_seeds(4);
  AddTrial(results, "static", "static", "none", 20);
  AddTrial(results, "static", "static", "live", 100);
  AddTrial(results, "sin_small", "sinusoidal", "none", 30);
  AddTrial(results, "sin_small", "sinusoidal", "live", 90);
  AddTrial(results, "sin_big", "sinusoidal", "none", 40);
  AddTrial(results, "sin_big", "sinusoidal", "live", 0, /*runs=*/0);
  AddTrial(results, "walk", "random_walk", "none", 10);
  AddTrial(results, "walk", "random_walk", "live", 110);
  return results;
}

template <typename T>
T Must(absl::StatusOr<T> value) {
  EXPECT_TRUE(value.ok()) << value.status();
  return value.ok() ? *std::move(value) : T{};
}

TEST(LearningCurvesFigureTest, DrawsTheIqmWithItsQuartileBandPerStepAndMode) {
  const GnuplotFigure figure = Must(LearningCurvesFigure(Results()));
  EXPECT_EQ(figure.name, "learning_curves");
  EXPECT_THAT(figure.title, HasSubstr("demo (sweep-7)"));
  ASSERT_EQ(figure.data.size(), 1u);
  EXPECT_THAT(Lines(figure.data[0].csv),
              IsSupersetOf({"panel,line,x,y,y_low,y_high,panel_title,label",
                            "0,0,0,0,0,0,observe: none,static",
                            "0,0,1000,11.5,10.75,12.25,observe: none,static",
                            "0,0,2000,21.5,20.75,22.25,observe: none,static",
                            "1,3,2000,111.5,110.75,112.25,observe: live,walk"}));
  // sin_big has no run in live: no rows, but its place (line 2) is kept.
  EXPECT_THAT(figure.data[0].csv, Not(HasSubstr("observe: live,sin_big")));
  const std::string& script = figure.script;
  EXPECT_THAT(script, HasSubstr("set multiplot layout 1,2"));
  EXPECT_THAT(script, HasSubstr("set title 'observe: none'"));
  EXPECT_THAT(script, HasSubstr("set title 'observe: live'"));
  EXPECT_THAT(script, HasSubstr("set xlabel 'environment steps'"));
  EXPECT_THAT(script, HasSubstr("set xtics ('0' 0, '500' 500, '1k' 1000, '1.5k' 1500, '2k' 2000)"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'avg_combined (IQM, Q1-Q3 band)'"));
  // The static baseline is black and dashed; a condition has one colour in every panel.
  EXPECT_THAT(script, HasSubstr("(sel(0, 0, 'y')) with lines lc rgb '#000000' lw 1.5 dt 2 "
                                "title 'static'"));
  EXPECT_THAT(script, HasSubstr("(sel(0, 1, 'y')) with lines lc rgb '#0072B2' lw 1.5 dt 1 "
                                "title 'sin_small'"));
  EXPECT_THAT(script, HasSubstr("(sel(1, 1, 'y')) with lines lc rgb '#0072B2' lw 1.5 dt 1 "
                                "title 'sin_small'"));
  EXPECT_THAT(script, HasSubstr("(sel(1, 3, 'y')) with lines lc rgb '#009E73'"));
  EXPECT_THAT(script, Not(HasSubstr("sel(1, 2,")));
}

TEST(LearningCurvesFigureTest, UsesTheQuartilesOfTheSeedsAtEachStep) {
  v1::SweepResults results;
  results.set_sweep_id("sweep-1");
  v1::TrialResults& trial = *results.add_trials();
  trial.set_condition("c");
  trial.set_family("sinusoidal");
  trial.set_observe("none");
  for (const double value : {10.0, 1.0, 3.0, 2.0}) *trial.add_runs() = MakeRun(0, {value});
  const GnuplotFigure figure = Must(LearningCurvesFigure(results));
  // IQM of {1, 2, 3, 10}: the mean of 2 and 3; quartiles by numpy's linear rule.
  EXPECT_THAT(figure.data[0].csv, HasSubstr("0,0,0,2.5,1.75,4.75,observe: none,c\n"));
}

TEST(LearningCurvesFigureTest, DrawsASecondStaticConditionInItsOwnColour) {
  v1::SweepResults results = Results();
  AddTrial(results, "static_pool", "static", "none", 25);
  const std::string script = Must(LearningCurvesFigure(results)).script;
  EXPECT_THAT(script, HasSubstr("(sel(0, 4, 'y')) with lines lc rgb '#E69F00' lw 1.5 dt 2 "
                                "title 'static_pool'"));
}

TEST(ContextReturnsFigureTest, GroupsContextsBySplitInOrderOfValue) {
  const GnuplotFigure figure = Must(ContextReturnsFigure(Results()));
  EXPECT_EQ(figure.name, "context_returns");
  const std::string& csv = figure.data[0].csv;
  // Four series in "none": bars 0.2 wide. Static's first bar: OOD-low 0.1, IQM 10 + 1.5.
  EXPECT_THAT(csv, HasSubstr("0,0,0,-0.3,11.5,10.75,12.25,OOD-low,0.1,static\n"));
  EXPECT_THAT(csv, HasSubstr("0,0,1,1.3,101.5,100.75,102.25,ID,0.4,static\n"));
  EXPECT_THAT(csv, HasSubstr("0,0,2,2.3,201.5,200.75,202.25,ID,0.6,static\n"));
  EXPECT_THAT(csv, HasSubstr("0,0,3,3.9,51.5,50.75,52.25,OOD-high,0.9,static\n"));
  EXPECT_THAT(csv, HasSubstr(",OOD-high,0.9,walk\n"));
  for (const std::string& line : Lines(csv)) {
    EXPECT_FALSE(line.starts_with("1,2,")) << line;  // sin_big has no run in live
  }
  const std::string& script = figure.script;
  EXPECT_THAT(script, HasSubstr("set xtics ('0.1' 0, '0.4' 1.6, '0.6' 2.6, '0.9' 4.2)"));
  EXPECT_THAT(script, HasSubstr("set label 'OOD-low'"));
  EXPECT_THAT(script, HasSubstr("set label 'ID'"));
  EXPECT_THAT(script, HasSubstr("set label 'OOD-high'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'mean return (IQM, Q1-Q3)'"));
  EXPECT_THAT(script, HasSubstr("with boxes fc rgb '#000000' fs solid 0.85 noborder title "
                                "'static'"));
}

TEST(FamilyHeatmapFigureTest, SubtractsStaticFromEachFamilysBestConditionPerMode) {
  const GnuplotFigure figure = Must(FamilyHeatmapFigure(Results()));
  EXPECT_EQ(figure.name, "family_heatmap");
  // none: static 21.5; sinusoidal's best is sin_big (41.5); random_walk 11.5.
  // live: static 101.5; sinusoidal has only sin_small (91.5); random_walk 111.5.
  EXPECT_THAT(Lines(figure.data[0].csv),
              ElementsAre("row,column,value,text_color,text,row_label,column_label",
                          "0,0,20,16777215,+20.0,sinusoidal,none",
                          "0,1,-10,0,-10.0,sinusoidal,live",
                          "1,0,-10,0,-10.0,random_walk,none",
                          "1,1,10,0,+10.0,random_walk,live"));
  EXPECT_THAT(figure.script, HasSubstr("set xlabel 'observe mode'"));
  EXPECT_THAT(figure.script, HasSubstr("set ylabel 'schedule family'"));
}

TEST(FamilyHeatmapFigureTest, LeavesACellWithoutAStaticBaselineEmpty) {
  v1::SweepResults results = Results();
  results.mutable_trials(1)->clear_runs();  // static, live
  const GnuplotFigure figure = Must(FamilyHeatmapFigure(results));
  EXPECT_THAT(figure.data[0].csv, HasSubstr("0,1,,0,n/a,sinusoidal,live\n"));
}

TEST(FamilyHeatmapFigureTest, NeedsAStaticConditionAndAFamily) {
  v1::SweepResults results = Results();
  results.mutable_trials(0)->clear_runs();
  results.mutable_trials(1)->clear_runs();
  EXPECT_EQ(FamilyHeatmapFigure(results).status().code(),
            absl::StatusCode::kFailedPrecondition);
  v1::SweepResults only_static;
  AddTrial(only_static, "static", "static", "none", 20);
  EXPECT_EQ(FamilyHeatmapFigure(only_static).status().code(),
            absl::StatusCode::kFailedPrecondition);
}

TEST(PerformanceProfilesFigureTest, StepsDownAtEachRunsScore) {
  const GnuplotFigure figure = Must(PerformanceProfilesFigure(Results()));
  EXPECT_EQ(figure.name, "performance_profiles");
  // Panel "none" spans the scores 10 to 43, with 5% margins: [8.35, 44.65].
  EXPECT_THAT(Lines(figure.data[0].csv),
              IsSupersetOf({"panel,line,x,y,panel_title,label",
                            "0,0,8.35,1,observe: none,static", "0,0,20,0.75,observe: none,static",
                            "0,0,21,0.5,observe: none,static", "0,0,22,0.25,observe: none,static",
                            "0,0,23,0,observe: none,static",
                            "0,0,44.65,0,observe: none,static"}));
  EXPECT_THAT(figure.script, HasSubstr("set xrange [8.35:44.65]"));
  EXPECT_THAT(figure.script, HasSubstr("set yrange [0:1.05]"));
  EXPECT_THAT(figure.script,
              HasSubstr("(sel(0, 0, 'y')) with steps lc rgb '#000000' lw 1.5 dt 2"));
  EXPECT_THAT(figure.script, HasSubstr("set ylabel 'fraction of runs with score > tau'"));
}

TEST(PerformanceProfilesFigureTest, CountsTiedScoresOnce) {
  v1::SweepResults results;
  v1::TrialResults& trial = *results.add_trials();
  trial.set_condition("c");
  trial.set_observe("none");
  for (const double last : {1.0, 2.0, 2.0, 4.0}) *trial.add_runs() = MakeRun(0, {last});
  const std::string csv = Must(PerformanceProfilesFigure(results)).data[0].csv;
  EXPECT_THAT(csv, HasSubstr("0,0,1,0.75,"));
  EXPECT_THAT(csv, HasSubstr("0,0,2,0.25,"));
  EXPECT_THAT(csv, Not(HasSubstr("0,0,2,0.5,")));
  EXPECT_THAT(csv, HasSubstr("0,0,4,0,"));
}

TEST(SweepFiguresTest, MakesEveryFigureInOrder) {
  const std::vector<GnuplotFigure> figures = Must(SweepFigures(Results(), v1::SweepReport()));
  std::vector<std::string> names;
  for (const GnuplotFigure& figure : figures) names.push_back(figure.name);
  EXPECT_THAT(names, ElementsAre("learning_curves", "context_returns", "family_heatmap",
                                 "performance_profiles"));
}

TEST(SweepFiguresTest, CoverageFigureHasABarPerConditionWithStandardErrorBars) {
  v1::SweepReport report;
  report.set_name("cov");
  EXPECT_EQ(CoverageFigure(report).status().code(), absl::StatusCode::kFailedPrecondition);
  v1::CoverageSection& section = *report.add_coverage();
  section.set_projection("state");
  section.set_cells(20736);
  section.add_tests()->set_mode("none");
  for (const auto& [condition, mean] : {std::pair("static", 6.5), std::pair("sinusoidal", 6.8)}) {
    v1::CoverageRow& row = *section.add_rows();
    row.set_condition(condition);
    row.set_mode("none");
    row.set_mean(mean);
    row.set_sem(0.25);
  }
  const GnuplotFigure figure = Must(CoverageFigure(report));
  EXPECT_EQ(figure.name, "coverage");
  ASSERT_EQ(figure.data.size(), 1u);
  const std::string& csv = figure.data[0].csv;
  EXPECT_THAT(csv, HasSubstr(",6.5,6.25,6.75,"));
  EXPECT_THAT(csv, HasSubstr(",6.8,6.55,7.05,"));
  EXPECT_THAT(figure.script, HasSubstr("state, observe: none"));
  EXPECT_THAT(figure.script, HasSubstr("% of 20736 cells (mean, SEM)"));
  std::vector<std::string> names;
  for (const GnuplotFigure& f : Must(SweepFigures(Results(), report))) names.push_back(f.name);
  EXPECT_EQ(names.back(), "coverage");
}

TEST(SweepFiguresTest, LeavesOutTheHeatmapWithoutAStaticBaseline) {
  v1::SweepResults results;
  AddTrial(results, "sin", "sinusoidal", "none", 20);
  const std::vector<GnuplotFigure> figures = Must(SweepFigures(results, v1::SweepReport()));
  ASSERT_EQ(figures.size(), 3u);
  EXPECT_EQ(figures[2].name, "performance_profiles");
}

TEST(SweepFiguresTest, RefusesSweepsWithoutRunsOrWithBrokenRuns) {
  v1::SweepResults results = Results();
  for (v1::TrialResults& trial : *results.mutable_trials()) trial.clear_runs();
  const absl::Status none = SweepFigures(results, v1::SweepReport()).status();
  EXPECT_EQ(none.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(none.message(), HasSubstr("sweep-7"));

  results = Results();
  results.mutable_trials(2)->mutable_runs(1)->clear_evaluations();
  const absl::Status empty = LearningCurvesFigure(results).status();
  EXPECT_EQ(empty.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(empty.message(), HasSubstr("sin_small"));

  results = Results();
  v1::Evaluation& last = *results.mutable_trials(0)->mutable_runs(0)->mutable_evaluations(2);
  last.mutable_contexts(0)->set_split(v1::SPLIT_UNSPECIFIED);
  EXPECT_EQ(ContextReturnsFigure(results).status().code(), absl::StatusCode::kDataLoss);
}

}  // namespace
}  // namespace dcs::report
