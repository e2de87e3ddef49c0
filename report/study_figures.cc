// Copyright 2026 The DCS Authors.
#include "report/study_figures.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "coordinator/study_sweep.h"
#include "report/heatmap_chart.h"
#include "report/line_chart.h"

namespace dcs::report {

absl::StatusOr<GnuplotFigure> StudyHistoryFigure(
    const coordinator::StudyRecord& study, const std::vector<coordinator::StudyTrial>& trials) {
  const bool minimize = study.submission.direction == coordinator::Direction::kMinimize;
  ChartLine values{.label = "objective", .points = true};
  ChartLine best{.label = "best so far", .steps = true};
  for (const coordinator::StudyTrial& trial : trials) {
    if (trial.state != coordinator::TrialState::kComplete || !std::isfinite(trial.value)) continue;
    const double number = static_cast<double>(trial.number);
    values.x.push_back(number);
    values.y.push_back(trial.value);
    const bool better = best.y.empty() || coordinator::IsBetter(study.submission.direction,
                                                                trial.value, best.y.back());
    best.x.push_back(number);
    best.y.push_back(better ? trial.value : best.y.back());
  }
  if (values.x.empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat(study.id, " has no complete trial with a finite value to draw"));
  }
  const std::string title =
      study.submission.name.empty() ? study.id : absl::StrCat(study.id, " ", study.submission.name);
  return LineChartFigure(
      {.name = absl::StrCat(study.id, "_history"),
       .title = absl::StrCat("Optimisation history of ", title),
       .panels = {{.title = title,
                   .x_label = "trial",
                   .y_label = "objective",
                   .lines = {values, best},
                   .legend = minimize ? LegendPlace::kTopRight : LegendPlace::kBottomRight}},
       .columns = 1,
       .panel_width = 640,
       .panel_height = 400});
}

absl::StatusOr<GnuplotFigure> StudyStageModesFigure(const v1::StudyReport& report) {
  const int modes = report.modes_size();
  if (report.top() == 0 || modes == 0) {
    return absl::FailedPreconditionError(
        absl::StrCat(report.study_id(), " has no best trials' stage modes to draw"));
  }
  Heatmap heatmap{.name = absl::StrCat(report.study_id(), "_stage_modes"),
                  .title = absl::StrCat("Stage modes of the best ", report.top(), " trials of ",
                                        report.name()),
                  .x_label = "mode",
                  .y_label = "stage",
                  .column_labels = {report.modes().begin(), report.modes().end()},
                  .value_label = "trials",
                  .decimals = 0,
                  .diverging = false};
  for (int k = 0; k < report.mode_counts_size() / modes; ++k) {
    heatmap.row_labels.push_back(absl::StrCat(k + 1));
    std::vector<double>& row = heatmap.values.emplace_back();
    for (int m = 0; m < modes; ++m) row.push_back(report.mode_counts(k * modes + m));
  }
  return HeatmapFigure(heatmap);
}

absl::StatusOr<GnuplotFigure> StudyRankShiftFigure(const v1::StudyReport& report) {
  // Ranks are drawn downwards (y = -rank), rank 1 at the top, each labelled.
  LinePanel panel{.title = report.name(),
                  .x_label = "",
                  .y_label = "rank (1 = best)",
                  .x_range = std::pair{-0.1, 1.1},
                  .x_tics = {{.at = 0, .label = "search"}, {.at = 1, .label = "retrain"}},
                  .legend = LegendPlace::kOutsideRight};
  int largest = 1;
  for (const v1::StudyReport::Trial& trial : report.trials()) {
    if (trial.rank() == 0 || trial.retrain_rank() == 0) continue;
    panel.lines.push_back(
        {.label = coordinator::StudyTrialCondition(trial.trial(), /*retrain=*/false),
         .x = {0, 1},
         .y = {-static_cast<double>(trial.rank()), -static_cast<double>(trial.retrain_rank())}});
    largest = std::max({largest, trial.rank(), trial.retrain_rank()});
  }
  if (panel.lines.empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat(report.study_id(), " has no retrained trial to draw"));
  }
  panel.y_range = std::pair{-largest - 0.5, -0.5};
  for (int rank = 1; rank <= largest; ++rank) {
    panel.y_tics.push_back({.at = -static_cast<double>(rank), .label = absl::StrCat(rank)});
  }
  return LineChartFigure({.name = absl::StrCat(report.study_id(), "_rank_shift"),
                          .title = absl::StrCat("Rank shift from search to retrain of ",
                                                report.name()),
                          .panels = {panel},
                          .columns = 1,
                          .panel_width = 640,
                          .panel_height = 520});
}

}  // namespace dcs::report
