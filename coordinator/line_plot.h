// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_LINE_PLOT_H_
#define DCS_COORDINATOR_LINE_PLOT_H_

// Renders figures made of small line-plot panels as standalone SVG documents: the schedule
// trajectories of `dcs schedule preview --svg` and the learning curves of the coordinator's
// reports. A figure is a grid of panels; each panel has a title, axes with "nice" tick values
// (1, 2 or 5 times a power of ten, 4 to 6 ticks; 2.5 times a power of ten when nothing else
// gives 4 to 6; fewer when their labels would crowd a small panel), grid lines, axis labels, a
// legend when its series have labels (at most three rows, then "+N more"; none in a panel too
// short for it, where a line's label is still its tooltip), and one thin polyline per series
// in a fixed colour-blind-safe palette (Okabe-Ito; series i has the same colour in every
// panel).
// Thread-safe (pure function).
//
// Text (titles, labels) is UTF-8 and is escaped for XML; text wider than its space is cut with
// an ellipsis. Coordinates are rounded to 0.1 px. Lines leaving a fixed axis range are clipped
// at the plot area.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"

namespace dcs::coordinator {

// One line: the points (x[i], y[i]) joined in the order given. REQUIRES x.size() == y.size().
// A series with one point is drawn as a dot; an empty one draws nothing.
struct Series {
  std::string label;  // shown in the panel's legend; empty: not in the legend
  std::vector<double> x;
  std::vector<double> y;
};

// One small plot. Each axis range is fixed by `*_range` (min < max) or else taken from the data:
// x from its minimum to its maximum, y with a 5% margin above and below. A constant or empty
// axis gets a span around its value (+-10% of it; [-1, 1] around 0; [0, 1] without data).
struct Panel {
  std::string title;  // above the panel
  std::string x_label, y_label;
  std::vector<Series> series;
  std::optional<std::pair<double, double>> y_range;  // fixed y axis, else from the data
  std::optional<std::pair<double, double>> x_range;  // fixed x axis, else from the data
  // Reference lines across the plot area, under the series: dashed vertical lines at these x
  // (e.g. episode boundaries), dotted horizontal lines at these y. Markers outside the axis
  // range are not drawn; they do not widen an axis taken from the data.
  std::vector<double> x_markers;
  std::vector<double> y_markers;
};

// Panels laid out in rows of `columns`, left to right, under the figure's title.
struct Figure {
  std::string title;  // on top of the figure; empty: no title band
  std::vector<Panel> panels;
  int columns = 3;          // panels per row; the figure is only as wide as the panels need
  int panel_width = 360;    // pixels, including the panel's title, tick labels and legend
  int panel_height = 220;
};

// Renders `figure` as a standalone SVG document: an XML declaration, then "<svg ...>" up to
// "</svg>\n". Each panel is a <g class="panel" id="panel-<i>"> holding a
// <rect class="plot-area" x=".." y=".." width=".." height=".."> and, per series, one
// <polyline class="series" points="x,y ..."> in the panel's coordinates (y grows downwards).
// Empty panels and series are allowed and drawn empty.
//
// INVALID_ARGUMENT if columns < 1, panel_width < 120 or panel_height < 100, a series has x and
// y of different lengths, a value, range bound or marker is NaN or infinite, a range has
// min >= max, or an axis's span overflows a double.
absl::StatusOr<std::string> RenderSvg(const Figure& figure);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_LINE_PLOT_H_
