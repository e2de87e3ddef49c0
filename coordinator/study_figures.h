// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STUDY_FIGURES_H_
#define DCS_COORDINATOR_STUDY_FIGURES_H_

// A study's figures, as gnuplot figures (coordinator/gnuplot_figure.h). Thread-safe (pure
// functions).

#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/gnuplot_figure.h"
#include "coordinator/run_store.h"

namespace dcs::coordinator {

// The optimisation history, as Optuna's plot_optimization_history draws it: each complete
// trial's value (a dot) and the best value so far (steps), against the trial number; the
// figure is named "<study id>_history". Values that are not finite are left out.
// FAILED_PRECONDITION if no trial has a finite value yet.
absl::StatusOr<GnuplotFigure> StudyHistoryFigure(const StudyRecord& study,
                                                 const std::vector<StudyTrial>& trials);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STUDY_FIGURES_H_
