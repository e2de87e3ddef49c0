// Copyright 2026 The DCS Authors.
#include "report/sweep_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "report/bar_chart.h"
#include "report/heatmap_chart.h"
#include "report/line_chart.h"

namespace dcs::report {
namespace {

constexpr char kStaticFamily[] = "static";
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaxFigureWidth = 1320;  // pixels

// The groups of the context figure, in the order they are drawn, with their display names.
constexpr std::pair<v1::Split, const char*> kSplitGroups[] = {
    {v1::SPLIT_OOD_LOW, "OOD-low"}, {v1::SPLIT_ID, "ID"}, {v1::SPLIT_OOD_HIGH, "OOD-high"}};

bool IsStatic(const v1::TrialResults& trial) { return trial.family() == kStaticFamily; }

// How each trial is drawn: its colour (by condition, shared by its modes) and dash.
struct TrialStyle {
  std::string color;
  bool dashed = false;
};

// The first static condition is black; any other static condition takes the next colour after
// the schedules' (dashed too).
std::vector<TrialStyle> TrialStyles(const v1::SweepResults& results) {
  std::map<std::string, int> condition_index;
  std::vector<std::string> statics;
  for (const v1::TrialResults& trial : results.trials()) {
    if (IsStatic(trial)) {
      if (std::find(statics.begin(), statics.end(), trial.condition()) == statics.end()) {
        statics.push_back(trial.condition());
      }
    } else {
      condition_index.emplace(trial.condition(), static_cast<int>(condition_index.size()));
    }
  }
  std::vector<TrialStyle> styles;
  for (const v1::TrialResults& trial : results.trials()) {
    if (!IsStatic(trial)) {
      styles.push_back({.color = SeriesColor(condition_index[trial.condition()])});
      continue;
    }
    const int nth = static_cast<int>(std::find(statics.begin(), statics.end(), trial.condition()) -
                                     statics.begin());
    styles.push_back(
        {.color = nth == 0 ? std::string(kBaselineColor)
                           : SeriesColor(static_cast<int>(condition_index.size()) + nth - 1),
         .dashed = true});
  }
  return styles;
}

// The observe modes in the order the trials first use them.
std::vector<std::string> Modes(const v1::SweepResults& results) {
  std::vector<std::string> modes;
  for (const v1::TrialResults& trial : results.trials()) {
    if (std::find(modes.begin(), modes.end(), trial.observe()) == modes.end()) {
      modes.push_back(trial.observe());
    }
  }
  return modes;
}

std::string PanelTitle(const std::string& mode) { return absl::StrCat("observe: ", mode); }

std::string SweepName(const v1::SweepResults& results) {
  return results.name().empty() ? results.sweep_id()
                                : absl::StrCat(results.name(), " (", results.sweep_id(), ")");
}

absl::Status CheckResults(const v1::SweepResults& results) {
  bool any_run = false;
  for (const v1::TrialResults& trial : results.trials()) {
    for (const v1::EvaluationLog& run : trial.runs()) {
      any_run = true;
      if (run.evaluations().empty()) {
        return absl::DataLossError(absl::StrCat("the run of condition '", trial.condition(),
                                                "' (observe ", trial.observe(), ") with seed ",
                                                run.seed(), " has no evaluations"));
      }
      for (const v1::ContextEvaluation& context : run.evaluations().rbegin()->contexts()) {
        if (context.split() < v1::SPLIT_ID || context.split() > v1::SPLIT_OOD_HIGH) {
          return absl::DataLossError(absl::StrCat(
              "the run of condition '", trial.condition(), "' (observe ", trial.observe(),
              ") with seed ", run.seed(), " has a context of no known split (", context.split(),
              ")"));
        }
      }
    }
  }
  if (!any_run) {
    return absl::FailedPreconditionError(
        absl::StrCat("sweep ", SweepName(results), " has no completed runs to plot yet"));
  }
  return absl::OkStatus();
}

// Legends beside the panels when they would crowd them.
LegendPlace LegendFor(size_t entries, LegendPlace inside) {
  return entries <= 4 ? inside : LegendPlace::kOutsideRight;
}

int PanelWidth(size_t entries, int inside_width) {
  return entries <= 4 ? inside_width : inside_width + 180;
}

// As many panels per row as fit a page (an index.html) without shrinking the text.
int ColumnsFor(int panel_width) { return std::max(1, kMaxFigureWidth / panel_width); }

double MaxStep(const v1::SweepResults& results) {
  double max = 0;
  for (const v1::TrialResults& trial : results.trials()) {
    for (const v1::EvaluationLog& run : trial.runs()) {
      for (const v1::Evaluation& evaluation : run.evaluations()) {
        max = std::max(max, static_cast<double>(evaluation.step()));
      }
    }
  }
  return max;
}

size_t MaxTrialsPerMode(const v1::SweepResults& results, const std::vector<std::string>& modes) {
  size_t most = 0;
  for (const std::string& mode : modes) {
    most = std::max<size_t>(most, std::count_if(results.trials().begin(), results.trials().end(),
                                                [&](const v1::TrialResults& trial) {
                                                  return trial.observe() == mode;
                                                }));
  }
  return most;
}

absl::StatusOr<ChartLine> LearningCurve(const v1::TrialResults& trial, const TrialStyle& style) {
  std::map<int64_t, std::vector<double>> by_step;
  for (const v1::EvaluationLog& run : trial.runs()) {
    for (const v1::Evaluation& evaluation : run.evaluations()) {
      by_step[evaluation.step()].push_back(evaluation.avg_combined());
    }
  }
  ChartLine line{.label = trial.condition(), .color = style.color, .dashed = style.dashed};
  for (const auto& [step, values] : by_step) {
    DCS_ASSIGN_OR_RETURN(const coordinator::IqmSummary summary, coordinator::SummarizeIqm(values));
    line.x.push_back(static_cast<double>(step));
    line.y.push_back(summary.iqm);
    line.y_low.push_back(summary.q1);
    line.y_high.push_back(summary.q3);
  }
  return line;
}

absl::StatusOr<double> LastIqm(const v1::TrialResults& trial) {
  std::vector<double> last;
  for (const v1::EvaluationLog& run : trial.runs()) last.push_back(run.last());
  return coordinator::InterquartileMean(last);
}

// The performance profile of `scores` over [lo, hi]: the fraction of scores > tau.
ChartLine Profile(std::vector<double> scores, double lo, double hi) {
  std::sort(scores.begin(), scores.end());
  const double n = static_cast<double>(scores.size());
  ChartLine line{.steps = true};
  line.x.push_back(lo);
  line.y.push_back(1);
  for (size_t i = 0; i < scores.size(); ++i) {
    if (i + 1 < scores.size() && scores[i + 1] == scores[i]) continue;  // the last of equals
    line.x.push_back(scores[i]);
    line.y.push_back(static_cast<double>(scores.size() - i - 1) / n);
  }
  line.x.push_back(hi);
  line.y.push_back(0);
  return line;
}

struct ContextKey {
  int split_order = 0;  // index in kSplitGroups
  double value = 0;
  auto operator<=>(const ContextKey&) const = default;
};

int SplitOrder(v1::Split split) {
  for (size_t i = 0; i < std::size(kSplitGroups); ++i) {
    if (kSplitGroups[i].first == split) return static_cast<int>(i);
  }
  return 0;  // CheckResults admits no other split
}

// Per context of the last evaluation, each run's mean return there.
std::map<ContextKey, std::vector<double>> LastContextMeans(const v1::TrialResults& trial) {
  std::map<ContextKey, std::vector<double>> means;
  for (const v1::EvaluationLog& run : trial.runs()) {
    for (const v1::ContextEvaluation& context : run.evaluations().rbegin()->contexts()) {
      means[{SplitOrder(context.split()), context.value()}].push_back(context.mean());
    }
  }
  return means;
}

}  // namespace

absl::StatusOr<GnuplotFigure> LearningCurvesFigure(const v1::SweepResults& results) {
  DCS_RETURN_IF_ERROR(CheckResults(results));
  const std::vector<TrialStyle> styles = TrialStyles(results);
  const std::vector<std::string> modes = Modes(results);
  const size_t entries = MaxTrialsPerMode(results, modes);
  const int panel_width = PanelWidth(entries, 440);
  LineChart chart{.name = "learning_curves",
                  .title = absl::StrCat("Learning curves: ", SweepName(results)),
                  .columns = ColumnsFor(panel_width),
                  .panel_width = panel_width,
                  .panel_height = 320};
  const std::vector<Tic> step_tics = CompactTics(MaxStep(results));
  for (const std::string& mode : modes) {
    LinePanel panel{.title = PanelTitle(mode),
                    .x_label = "environment steps",
                    .y_label = "avg_combined (IQM, Q1-Q3 band)",
                    .x_tics = step_tics,
                    .legend = LegendFor(entries, LegendPlace::kBottomRight)};
    for (int t = 0; t < results.trials_size(); ++t) {
      if (results.trials(t).observe() != mode) continue;
      DCS_ASSIGN_OR_RETURN(ChartLine line, LearningCurve(results.trials(t), styles[t]));
      panel.lines.push_back(std::move(line));
    }
    chart.panels.push_back(std::move(panel));
  }
  return LineChartFigure(chart);
}

absl::StatusOr<GnuplotFigure> ContextReturnsFigure(const v1::SweepResults& results) {
  DCS_RETURN_IF_ERROR(CheckResults(results));
  const std::vector<TrialStyle> styles = TrialStyles(results);
  BarChart chart{.name = "context_returns",
                 .title = absl::StrCat("Returns per evaluation context at the last evaluation: ",
                                       SweepName(results)),
                 .columns = 1,
                 .panel_width = 980,
                 .panel_height = 320};
  for (const std::string& mode : Modes(results)) {
    std::vector<int> trials;
    std::vector<std::map<ContextKey, std::vector<double>>> means;
    std::map<ContextKey, int> categories;  // ordered; the index is filled in below
    for (int t = 0; t < results.trials_size(); ++t) {
      if (results.trials(t).observe() != mode) continue;
      trials.push_back(t);
      means.push_back(LastContextMeans(results.trials(t)));
      for (const auto& [key, values] : means.back()) categories[key] = 0;
    }
    BarPanel panel{.title = PanelTitle(mode),
                   .x_label = "evaluation context (value of the varied feature)",
                   .y_label = "mean return (IQM, Q1-Q3)"};
    for (auto& [key, index] : categories) {
      index = static_cast<int>(panel.categories.size());
      panel.categories.push_back({.label = absl::StrFormat("%g", key.value),
                                  .group = kSplitGroups[key.split_order].second});
    }
    for (size_t i = 0; i < trials.size(); ++i) {
      const v1::TrialResults& trial = results.trials(trials[i]);
      BarSeries series{.label = trial.condition(),
                       .y = std::vector<double>(categories.size(), kNaN),
                       .y_low = std::vector<double>(categories.size(), kNaN),
                       .y_high = std::vector<double>(categories.size(), kNaN),
                       .color = styles[trials[i]].color};
      for (const auto& [key, values] : means[i]) {
        DCS_ASSIGN_OR_RETURN(const coordinator::IqmSummary summary,
                             coordinator::SummarizeIqm(values));
        const int c = categories[key];
        series.y[c] = summary.iqm;
        series.y_low[c] = summary.q1;
        series.y_high[c] = summary.q3;
      }
      panel.series.push_back(std::move(series));
    }
    chart.panels.push_back(std::move(panel));
  }
  return BarChartFigure(chart);
}

absl::StatusOr<GnuplotFigure> FamilyHeatmapFigure(const v1::SweepResults& results) {
  DCS_RETURN_IF_ERROR(CheckResults(results));
  const std::vector<std::string> modes = Modes(results);
  std::vector<double> static_iqm(modes.size(), kNaN);
  std::vector<std::string> families;
  std::map<std::string, std::vector<double>> best;  // family -> per mode
  for (const v1::TrialResults& trial : results.trials()) {
    if (trial.runs().empty()) continue;
    const size_t m = std::find(modes.begin(), modes.end(), trial.observe()) - modes.begin();
    DCS_ASSIGN_OR_RETURN(const double iqm, LastIqm(trial));
    if (IsStatic(trial)) {
      if (std::isnan(static_iqm[m])) static_iqm[m] = iqm;
      continue;
    }
    auto [it, added] = best.emplace(trial.family(), std::vector<double>(modes.size(), kNaN));
    if (added) families.push_back(trial.family());
    if (std::isnan(it->second[m]) || iqm > it->second[m]) it->second[m] = iqm;
  }
  if (families.empty() ||
      std::all_of(static_iqm.begin(), static_iqm.end(), [](double v) { return std::isnan(v); })) {
    return absl::FailedPreconditionError(absl::StrCat(
        "sweep ", SweepName(results),
        " needs completed runs of a static condition and of a schedule family for the heatmap"));
  }
  Heatmap heatmap{.name = "family_heatmap",
                  .title = absl::StrCat("Each family's best condition minus static: ",
                                        SweepName(results)),
                  .x_label = "observe mode",
                  .y_label = "schedule family",
                  .column_labels = modes,
                  .row_labels = families,
                  .value_label = "IQM of last avg_combined, minus static"};
  for (const std::string& family : families) {
    std::vector<double> row(modes.size(), kNaN);
    for (size_t m = 0; m < modes.size(); ++m) row[m] = best[family][m] - static_iqm[m];
    heatmap.values.push_back(std::move(row));
  }
  return HeatmapFigure(heatmap);
}

absl::StatusOr<GnuplotFigure> PerformanceProfilesFigure(const v1::SweepResults& results) {
  DCS_RETURN_IF_ERROR(CheckResults(results));
  const std::vector<TrialStyle> styles = TrialStyles(results);
  const std::vector<std::string> modes = Modes(results);
  const size_t entries = MaxTrialsPerMode(results, modes);
  const int panel_width = PanelWidth(entries, 440);
  LineChart chart{.name = "performance_profiles",
                  .title = absl::StrCat("Performance profiles: ", SweepName(results)),
                  .columns = ColumnsFor(panel_width),
                  .panel_width = panel_width,
                  .panel_height = 320};
  for (const std::string& mode : modes) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const v1::TrialResults& trial : results.trials()) {
      if (trial.observe() != mode) continue;
      for (const v1::EvaluationLog& run : trial.runs()) {
        lo = std::min(lo, run.last());
        hi = std::max(hi, run.last());
      }
    }
    LinePanel panel{.title = PanelTitle(mode),
                    .x_label = "tau (avg_combined at the last evaluation)",
                    .y_label = "fraction of runs with score > tau",
                    .y_range = std::make_pair(0.0, 1.05),
                    .legend = LegendFor(entries, LegendPlace::kBottomLeft)};
    if (lo <= hi) {
      const double margin = hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.1 * std::abs(lo));
      lo -= margin;
      hi += margin;
      panel.x_range = std::make_pair(lo, hi);
    }
    for (int t = 0; t < results.trials_size(); ++t) {
      const v1::TrialResults& trial = results.trials(t);
      if (trial.observe() != mode) continue;
      ChartLine line{.label = trial.condition()};
      if (!trial.runs().empty()) {
        std::vector<double> scores;
        for (const v1::EvaluationLog& run : trial.runs()) scores.push_back(run.last());
        line = Profile(std::move(scores), lo, hi);
        line.label = trial.condition();
      }
      line.color = styles[t].color;
      line.dashed = styles[t].dashed;
      panel.lines.push_back(std::move(line));
    }
    chart.panels.push_back(std::move(panel));
  }
  return LineChartFigure(chart);
}

absl::StatusOr<GnuplotFigure> CoverageFigure(const v1::SweepReport& report) {
  if (report.coverage().empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat("sweep ", report.name(), " has no runs that counted coverage"));
  }
  BarChart chart{.name = "coverage",
                 .title = absl::StrCat("Coverage: ", report.name())};
  size_t most_rows = 0;
  for (const v1::CoverageSection& section : report.coverage()) {
    for (const v1::CoverageTest& test : section.tests()) {
      BarPanel panel{.title = absl::StrCat(section.projection(), ", ", PanelTitle(test.mode())),
                     .x_label = "condition",
                     .y_label = absl::StrCat("% of ", section.cells(), " cells (mean, SEM)"),
                     .legend = LegendPlace::kNone};
      BarSeries series;
      for (const v1::CoverageRow& row : section.rows()) {
        if (row.mode() != test.mode()) continue;
        panel.categories.push_back({.label = row.condition()});
        series.y.push_back(row.mean());
        series.y_low.push_back(row.mean() - row.sem());
        series.y_high.push_back(row.mean() + row.sem());
      }
      most_rows = std::max(most_rows, panel.categories.size());
      panel.series.push_back(std::move(series));
      chart.panels.push_back(std::move(panel));
    }
  }
  // Room for each condition's name under its bar.
  chart.panel_width = std::max(640, static_cast<int>(90 * most_rows));
  chart.columns = ColumnsFor(chart.panel_width);
  return BarChartFigure(chart);
}

absl::StatusOr<std::vector<GnuplotFigure>> SweepFigures(const v1::SweepResults& results,
                                                        const v1::SweepReport& report) {
  std::vector<GnuplotFigure> figures;
  DCS_ASSIGN_OR_RETURN(GnuplotFigure curves, LearningCurvesFigure(results));
  figures.push_back(std::move(curves));
  DCS_ASSIGN_OR_RETURN(GnuplotFigure contexts, ContextReturnsFigure(results));
  figures.push_back(std::move(contexts));
  absl::StatusOr<GnuplotFigure> heatmap = FamilyHeatmapFigure(results);
  if (heatmap.ok()) {
    figures.push_back(*std::move(heatmap));
  } else if (!absl::IsFailedPrecondition(heatmap.status())) {
    return heatmap.status();
  }
  DCS_ASSIGN_OR_RETURN(GnuplotFigure profiles, PerformanceProfilesFigure(results));
  figures.push_back(std::move(profiles));
  if (!report.coverage().empty()) {
    DCS_ASSIGN_OR_RETURN(GnuplotFigure coverage, CoverageFigure(report));
    figures.push_back(std::move(coverage));
  }
  return figures;
}

}  // namespace dcs::report
