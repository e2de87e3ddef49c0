// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_GENERALIZATION_MAP_H_
#define DCS_REPORT_GENERALIZATION_MAP_H_

// Generalisation maps as gnuplot figures (report/gnuplot_figure.h): trained policies' mean
// returns over a grid of one or two context features (`dcs eval`). One feature gives a line per
// policy, with a band of one standard deviation of the episodes' returns; two give a heatmap
// per policy, on one colour scale (viridis, perceptually uniform and colour-blind safe) so that
// panels compare. Each panel marks where its policy trained: a feature the run varied spans its
// training range (dashed) with its pool's values as points; any other feature sits at the
// run's value of it. Thread-safe (pure functions).
//
// Lines: as report/line_chart.h. Heatmaps: the data is `<name>.csv`, a row per cell,
//   panel,x,y,mean,std
// the first feature varying fastest; training contexts are drawn from the script itself.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

// One grid axis: a feature's values, ascending.
struct MapAxis {
  std::string feature;
  std::vector<double> values;
};

// Where one policy trained, along one axis: the varied feature's range and pool, or one value.
struct TrainingSpan {
  double low = 0;
  double high = 0;            // = low for a feature held at one value
  std::vector<double> pool;  // the varied feature's pool; empty otherwise
};

struct MapPolicy {
  std::string label;           // e.g. "run-7 @ 150k"
  std::vector<double> means;   // per cell, the first axis fastest
  std::vector<double> stds;    // per cell
  std::vector<TrainingSpan> training;  // per axis
};

struct GeneralizationMap {
  std::string name;  // file stem (CheckFigureName)
  std::string title;
  std::vector<MapAxis> axes;  // one or two
  std::vector<MapPolicy> policies;
  std::string value_label = "mean return";
};

// The map as a gnuplot figure. INVALID_ARGUMENT for a bad name, not one or two axes, an axis
// without values, no policies, a policy without a mean, std and span per cell and axis, or a
// value that is not finite.
absl::StatusOr<GnuplotFigure> GeneralizationMapFigure(const GeneralizationMap& map);

}  // namespace dcs::report

#endif  // DCS_REPORT_GENERALIZATION_MAP_H_
