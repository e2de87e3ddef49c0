// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_HEATMAP_CHART_H_
#define DCS_REPORT_HEATMAP_CHART_H_

// Heatmaps as gnuplot figures (report/gnuplot_figure.h): a grid of cells, each coloured
// by its value on a diverging palette centred at 0 (vermillion below, white at 0, blue above:
// Okabe-Ito's, colour-blind safe), with the value printed in the cell; cells without a value
// are grey and read "n/a" (the per-family heatmap relative to static). Thread-safe (pure
// functions).
//
// The figure's data is one CSV, `<name>.csv`: a row per cell,
//   row,column,value,text_color,text,row_label,column_label
// (value empty for a cell without one; text_color 0 for black, 16777215 for white, as gnuplot's
// `textcolor rgb variable` reads it; text last).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

struct Heatmap {
  std::string name;  // file stem (CheckFigureName)
  std::string title;
  std::string x_label;  // under the column labels
  std::string y_label;
  std::vector<std::string> column_labels;
  std::vector<std::string> row_labels;  // the first row is drawn at the top
  std::vector<std::vector<double>> values;  // values[row][column]; NaN: no value
  std::string value_label;  // the colour bar's
  int decimals = 1;  // of the numbers in the cells, which carry their sign ("+12.3", "-0.4")
  // Counts and other values >= 0: a scale from white at 0 to blue, numbers without a sign.
  bool diverging = true;
};

// The heatmap as a gnuplot figure; the colour scale spans [-m, m] ([0, m] if not diverging), m
// the largest |value| (1 without values). INVALID_ARGUMENT for a bad name, no rows or columns, not a row of values
// per row label, a row of another length than the column labels, an infinite value, or
// decimals outside [0, 6].
absl::StatusOr<GnuplotFigure> HeatmapFigure(const Heatmap& heatmap);

}  // namespace dcs::report

#endif  // DCS_REPORT_HEATMAP_CHART_H_
