// Copyright 2026 The DCS Authors.
#include "coordinator/study_figures.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "coordinator/line_chart.h"

namespace dcs::coordinator {

absl::StatusOr<GnuplotFigure> StudyHistoryFigure(const StudyRecord& study,
                                                 const std::vector<StudyTrial>& trials) {
  const bool minimize = study.submission.direction == Direction::kMinimize;
  ChartLine values{.label = "objective", .points = true};
  ChartLine best{.label = "best so far", .steps = true};
  for (const StudyTrial& trial : trials) {
    if (trial.state != TrialState::kComplete || !std::isfinite(trial.value)) continue;
    const double number = static_cast<double>(trial.number);
    values.x.push_back(number);
    values.y.push_back(trial.value);
    const bool better =
        best.y.empty() || IsBetter(study.submission.direction, trial.value, best.y.back());
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

}  // namespace dcs::coordinator
