// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_BAR_CHART_H_
#define DCS_REPORT_BAR_CHART_H_

// Grouped bar charts as gnuplot figures (report/gnuplot_figure.h): in each panel a
// cluster of bars per category, one bar per series, with optional error bars; consecutive
// categories of the same group stand together, apart from the next group, under the group's
// name (per-context returns: contexts grouped OOD-low / ID / OOD-high, a bar per condition).
// Thread-safe (pure functions).
//
// The figure's data is one CSV, `<name>.csv`: a row per bar,
//   panel,series,category,x,y,y_low,y_high,group,category_label,label
// (x the bar's centre; y_low and y_high empty without error bars; text last).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

struct BarCategory {
  std::string label;  // under its cluster, e.g. "0.35"
  std::string group;  // e.g. "ID"; empty: no group name
};

struct BarSeries {
  std::string label;  // in the legend
  // A value per category of the panel; NaN: no bar there.
  std::vector<double> y;
  // Error bars from y_low[i] to y_high[i]; empty: none.
  std::vector<double> y_low;
  std::vector<double> y_high;
  std::string color;  // "#rrggbb"; empty: SeriesColor(the series' index in its panel)
};

// The y axis spans the bars, error bars and 0, with room above for the group names.
struct BarPanel {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<BarCategory> categories;
  std::vector<BarSeries> series;
  LegendPlace legend = LegendPlace::kOutsideRight;
};

struct BarChart {
  std::string name;  // file stem (CheckFigureName)
  std::string title;
  std::vector<BarPanel> panels;
  int columns = 2;
  int panel_width = 560;  // pixels
  int panel_height = 300;
};

// The chart as a gnuplot figure. INVALID_ARGUMENT for a bad name, no panels, columns < 1,
// panels smaller than 160 x 120 pixels, a series without a value per category (or error bars
// of another length), an infinite value, or a NaN error bar under a bar.
absl::StatusOr<GnuplotFigure> BarChartFigure(const BarChart& chart);

}  // namespace dcs::report

#endif  // DCS_REPORT_BAR_CHART_H_
