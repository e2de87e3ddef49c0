// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_LINE_CHART_H_
#define DCS_REPORT_LINE_CHART_H_

// Line charts as gnuplot figures (report/gnuplot_figure.h): a grid of small line plots
// (gnuplot's multiplot), each line optionally with a shaded band (learning curves: the IQM with
// its Q1-Q3 band), dashed (a baseline) or drawn as steps (performance profiles), and reference
// lines across a panel (episode boundaries). Thread-safe (pure functions).
//
// The figure's data is one CSV, `<name>.csv`: a row per point,
//   panel,line,x,y[,y_low,y_high],panel_title,label
// (the band columns when any line has a band; text last, since gnuplot splits quoted fields).
// Its script plots each line from that file, selecting its rows by panel and line index.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

// The points (x[i], y[i]) joined in the order given; one point is drawn as a dot. An empty
// line draws nothing but keeps its colour.
struct ChartLine {
  std::string label;  // in the panel's legend; empty: not in the legend
  std::vector<double> x;
  std::vector<double> y;
  // A shaded band from y_low[i] to y_high[i] under the line; empty: none.
  std::vector<double> y_low;
  std::vector<double> y_high;
  std::string color;  // "#rrggbb"; empty: SeriesColor(the line's index in its panel)
  bool dashed = false;
  bool steps = false;  // a step function: y[i] holds from x[i] up to x[i + 1]
  bool points = false;  // dots at the points, not joined (a scatter)
};

// A tick mark on an axis, with its label (empty: the number, as gnuplot writes it).
struct Tic {
  double at = 0;
  std::string label;
};

// Ticks from 0 to `max` (> 0; else none), 1, 2, 2.5 or 5 times a power of ten apart, 4 to 8
// of them, labelled with a k or M suffix ("0", "25k", "1.5M"): environment steps.
std::vector<Tic> CompactTics(double max);

// One small plot. An axis range is fixed by `*_range` (min < max), else gnuplot takes it from
// the data (x exactly, y out to the next tick).
struct LinePanel {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<ChartLine> lines;
  std::optional<std::pair<double, double>> x_range;
  std::optional<std::pair<double, double>> y_range;
  // Grey reference lines across the plot: dashed vertical ones at these x, dotted horizontal
  // ones at these y; those outside the axis range (fixed, or else the data's) are left out.
  std::vector<double> x_markers;
  std::vector<double> y_markers;
  // The axes' ticks; empty: gnuplot picks them.
  std::vector<Tic> x_tics;
  std::vector<Tic> y_tics;
  LegendPlace legend = LegendPlace::kTopRight;
};

// Panels in rows of `columns`, left to right, under the figure's title.
struct LineChart {
  std::string name;  // file stem (CheckFigureName)
  std::string title;
  std::vector<LinePanel> panels;
  int columns = 3;
  int panel_width = 400;  // pixels
  int panel_height = 280;
};

// The chart as a gnuplot figure. INVALID_ARGUMENT for a bad name, no panels, columns < 1,
// panels smaller than 160 x 120 pixels, a line whose x, y (and band) differ in length, a value,
// marker or tick that is NaN or infinite, or a range with min >= max.
absl::StatusOr<GnuplotFigure> LineChartFigure(const LineChart& chart);

}  // namespace dcs::report

#endif  // DCS_REPORT_LINE_CHART_H_
