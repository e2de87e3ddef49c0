// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_STUDY_FIGURES_H_
#define DCS_REPORT_STUDY_FIGURES_H_

// A study's figures, as gnuplot figures (report/gnuplot_figure.h). Thread-safe (pure
// functions).

#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/study_table.h"
#include "dcs/v1/report.pb.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

// The optimisation history, as Optuna's plot_optimization_history draws it: each complete
// trial's value (a dot) and the best value so far (steps), against the trial number; the
// figure is named "<study id>_history". Values that are not finite are left out.
// FAILED_PRECONDITION if no trial has a finite value yet.
absl::StatusOr<GnuplotFigure> StudyHistoryFigure(
    const coordinator::StudyRecord& study, const std::vector<coordinator::StudyTrial>& trials);

// The paper's stage-mode heatmap: how many of the report's best trials (StudyReport.top) took
// each mode (columns) in each stage (rows); named "<study id>_stage_modes". FAILED_PRECONDITION
// if the report counted none (no complete trial, or a space without stage modes).
absl::StatusOr<GnuplotFigure> StudyStageModesFigure(const v1::StudyReport& report);

// The paper's rank-shift figure: each retrained trial's rank in the search (left) joined to its
// rank after retraining (right); named "<study id>_rank_shift". FAILED_PRECONDITION if no
// retrained trial has both ranks yet.
absl::StatusOr<GnuplotFigure> StudyRankShiftFigure(const v1::StudyReport& report);

}  // namespace dcs::report

#endif  // DCS_REPORT_STUDY_FIGURES_H_
