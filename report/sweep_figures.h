// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SWEEP_FIGURES_H_
#define DCS_REPORT_SWEEP_FIGURES_H_

// The figures of a sweep's report (`dcs plot`), as gnuplot figures (report/gnuplot_figure.h)
// from what its completed runs evaluated to (v1::SweepResults). Statistics across seeds are the
// paper's (coordinator/iqm.h): the IQM with the first and third quartiles. A panel per observe
// mode, in the order the trials first use them; in each, a line or bar per condition in the
// spec's order. A condition keeps its colour in every panel and figure (Okabe-Ito, in the order
// of the non-static conditions); the static baseline (family "static") is black and dashed (a
// second static condition takes the next colour, dashed).
// Thread-safe (pure functions).

#include <vector>

#include "absl/status/statusor.h"
#include "dcs/v1/report.pb.h"
#include "dcs/v1/sweep.pb.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

// "learning_curves": x the environment step of each evaluation, y the IQM across seeds of
// avg_combined at that step with its Q1-Q3 band.
absl::StatusOr<GnuplotFigure> LearningCurvesFigure(const v1::SweepResults& results);

// "context_returns": per evaluation context of the last evaluation, the IQM across seeds of the
// context's mean return, with Q1-Q3 error bars; contexts grouped OOD-low, ID, OOD-high, in
// order of value.
absl::StatusOr<GnuplotFigure> ContextReturnsFigure(const v1::SweepResults& results);

// "family_heatmap" (the paper's cross-environment figure): a row per schedule family with
// completed runs (static aside, multi_stage included), a column per observe mode; each cell the
// IQM across seeds of `last` (avg_combined at the last evaluation) of the family's best
// condition in that mode, minus the static baseline's IQM in the same mode (the first static
// condition of that mode; "n/a" without one). FAILED_PRECONDITION if the sweep has no static
// condition or no other family with completed runs.
absl::StatusOr<GnuplotFigure> FamilyHeatmapFigure(const v1::SweepResults& results);

// "performance_profiles": per condition, the fraction of its runs whose `last` exceeds tau,
// against tau (a step line; rliable's performance profile).
absl::StatusOr<GnuplotFigure> PerformanceProfilesFigure(const v1::SweepResults& results);

// "coverage" (the paper's coverage figure, §4.4): from the coverage sections of `report`
// (report/coverage_report.h), a panel per state projection and observe mode, a bar per
// condition: its runs' mean coverage (percent of the projection's cells visited over the run)
// with error bars of one standard error. FAILED_PRECONDITION if the report has no coverage.
absl::StatusOr<GnuplotFigure> CoverageFigure(const v1::SweepReport& report);

// Every figure above that `results` and their `report` (BuildSweepReport's) allow, in that
// order: the heatmap and the coverage figure are left out when they would be
// FAILED_PRECONDITION.
absl::StatusOr<std::vector<GnuplotFigure>> SweepFigures(const v1::SweepResults& results,
                                                        const v1::SweepReport& report);

// Each function above: FAILED_PRECONDITION naming the sweep if no trial has a completed run;
// DATA_LOSS naming the condition and seed for a run without evaluations or with a context of
// no known split.

}  // namespace dcs::report

#endif  // DCS_REPORT_SWEEP_FIGURES_H_
