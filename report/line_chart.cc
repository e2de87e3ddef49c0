// Copyright 2026 The DCS Authors.
#include "report/line_chart.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::report {
namespace {

constexpr char kMarkerColor[] = "#8c8c8c";

bool AllFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

bool TicsFinite(const std::vector<Tic>& tics) {
  return std::all_of(tics.begin(), tics.end(),
                     [](const Tic& tic) { return std::isfinite(tic.at); });
}

absl::Status CheckRange(const std::optional<std::pair<double, double>>& range,
                        const std::string& where) {
  if (!range.has_value()) return absl::OkStatus();
  if (!std::isfinite(range->first) || !std::isfinite(range->second) ||
      range->first >= range->second) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": a range needs finite min < max, not [", range->first, ", ",
                     range->second, "]"));
  }
  return absl::OkStatus();
}

absl::Status CheckLine(const ChartLine& line, const std::string& where) {
  const size_t n = line.x.size();
  const bool has_band = !line.y_low.empty() || !line.y_high.empty();
  if (line.y.size() != n || (has_band && (line.y_low.size() != n || line.y_high.size() != n))) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": x, y and the band must have as many values (x ", n, ", y ",
                     line.y.size(), ", band ", line.y_low.size(), " and ", line.y_high.size(),
                     ")"));
  }
  if (!AllFinite(line.x) || !AllFinite(line.y) || !AllFinite(line.y_low) ||
      !AllFinite(line.y_high)) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": values must be finite"));
  }
  return absl::OkStatus();
}

absl::Status CheckChart(const LineChart& chart) {
  DCS_RETURN_IF_ERROR(CheckPanelGrid("line chart", chart.name, chart.panels.size(),
                                     chart.columns, chart.panel_width, chart.panel_height));
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    const LinePanel& panel = chart.panels[p];
    const std::string where = absl::StrCat("line chart '", chart.name, "', panel ", p);
    DCS_RETURN_IF_ERROR(CheckRange(panel.x_range, where));
    DCS_RETURN_IF_ERROR(CheckRange(panel.y_range, where));
    if (!AllFinite(panel.x_markers) || !AllFinite(panel.y_markers) ||
        !TicsFinite(panel.x_tics) || !TicsFinite(panel.y_tics)) {
      return absl::InvalidArgumentError(absl::StrCat(where, ": markers and ticks must be finite"));
    }
    for (size_t l = 0; l < panel.lines.size(); ++l) {
      DCS_RETURN_IF_ERROR(CheckLine(panel.lines[l], absl::StrCat(where, ", line ", l)));
    }
  }
  return absl::OkStatus();
}

bool HasBand(const ChartLine& line) { return !line.y_low.empty(); }

bool AnyBand(const LineChart& chart) {
  for (const LinePanel& panel : chart.panels) {
    if (std::any_of(panel.lines.begin(), panel.lines.end(), HasBand)) return true;
  }
  return false;
}

std::string Csv(const LineChart& chart, bool bands) {
  std::string csv = absl::StrCat("panel,line,x,y,", bands ? "y_low,y_high," : "",
                                 "panel_title,label\n");
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    const LinePanel& panel = chart.panels[p];
    const std::string panel_title = CsvField(panel.title);
    for (size_t l = 0; l < panel.lines.size(); ++l) {
      const ChartLine& line = panel.lines[l];
      const std::string label = CsvField(line.label);
      for (size_t i = 0; i < line.x.size(); ++i) {
        absl::StrAppend(&csv, p, ",", l, ",", CsvNumber(line.x[i]), ",", CsvNumber(line.y[i]),
                        ",");
        if (bands) {
          if (HasBand(line)) {
            absl::StrAppend(&csv, CsvNumber(line.y_low[i]), ",", CsvNumber(line.y_high[i]), ",");
          } else {
            absl::StrAppend(&csv, ",,");
          }
        }
        absl::StrAppend(&csv, panel_title, ",", label, "\n");
      }
    }
  }
  return csv;
}

// The extent of the panel's values along x (`along_x`) or y (bands included); nullopt if it
// has no points.
std::optional<std::pair<double, double>> DataExtent(const LinePanel& panel, bool along_x) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const ChartLine& line : panel.lines) {
    for (const std::vector<double>* values :
         {along_x ? &line.x : &line.y, along_x ? &line.x : &line.y_low,
          along_x ? &line.x : &line.y_high}) {
      for (const double v : *values) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
  }
  if (lo > hi) return std::nullopt;
  return std::make_pair(lo, hi);
}

std::vector<double> MarkersInside(const std::vector<double>& markers,
                                  const std::optional<std::pair<double, double>>& range) {
  std::vector<double> inside;
  if (!range.has_value()) return inside;
  for (const double m : markers) {
    if (m >= range->first && m <= range->second) inside.push_back(m);
  }
  return inside;
}

std::string RangeCommand(const char* axis, const std::optional<std::pair<double, double>>& range,
                         bool fix) {
  if (range.has_value()) {
    return absl::StrCat("set ", axis, "range [", CsvNumber(range->first), ":",
                        CsvNumber(range->second), "]\n");
  }
  return absl::StrCat("set autoscale ", axis, fix ? "fix" : "", "\n");
}

std::string TicsCommand(const char* axis, const std::vector<Tic>& tics) {
  if (tics.empty()) return absl::StrCat("set ", axis, "tics autofreq\n");
  std::vector<std::string> positions;
  for (const Tic& tic : tics) {
    positions.push_back(tic.label.empty()
                            ? CsvNumber(tic.at)
                            : absl::StrCat(GnuplotString(tic.label), " ", CsvNumber(tic.at)));
  }
  return absl::StrCat("set ", axis, "tics (", absl::StrJoin(positions, ", "), ")\n");
}

std::string PanelKeyCommand(const LinePanel& panel) {
  const bool labelled = std::any_of(panel.lines.begin(), panel.lines.end(),
                                    [](const ChartLine& line) { return !line.label.empty(); });
  return KeyCommand(labelled ? panel.legend : LegendPlace::kNone);
}

std::string LineStyle(const ChartLine& line, size_t index) {
  const std::string color = line.color.empty() ? SeriesColor(static_cast<int>(index)) : line.color;
  if (line.points || line.x.size() == 1) {
    return absl::StrCat("with points pt 7 ps 0.6 lc rgb '", color, "'");
  }
  return absl::StrCat("with ", line.steps ? "steps" : "lines", " lc rgb '", color,
                      "' lw 1.5 dt ", line.dashed ? "2" : "1");
}

std::string PanelScript(const LinePanel& panel, size_t p) {
  const std::optional<std::pair<double, double>> x_extent =
      panel.x_range.has_value() ? panel.x_range : DataExtent(panel, /*along_x=*/true);
  const std::optional<std::pair<double, double>> y_extent =
      panel.y_range.has_value() ? panel.y_range : DataExtent(panel, /*along_x=*/false);
  std::string out = absl::StrCat("# Panel ", p, "\n", "set title ", GnuplotString(panel.title),
                                 " font sprintf(',%d', fontsize + 1)\n",
                                 "set xlabel ", GnuplotString(panel.x_label), "\n",
                                 "set ylabel ", GnuplotString(panel.y_label), "\n",
                                 "unset arrow\nunset label\n", PanelKeyCommand(panel));
  for (const double x : MarkersInside(panel.x_markers, x_extent)) {
    absl::StrAppend(&out, "set arrow from first ", CsvNumber(x), ", graph 0 to first ",
                    CsvNumber(x), ", graph 1 nohead back lc rgb '", kMarkerColor,
                    "' lw 1 dt 2\n");
  }
  for (const double y : MarkersInside(panel.y_markers, y_extent)) {
    absl::StrAppend(&out, "set arrow from graph 0, first ", CsvNumber(y), " to graph 1, first ",
                    CsvNumber(y), " nohead back lc rgb '", kMarkerColor, "' lw 1 dt 3\n");
  }
  if (!DataExtent(panel, /*along_x=*/true).has_value()) {  // no data: an empty frame
    const std::pair<double, double> unit(0.0, 1.0);
    absl::StrAppend(&out, RangeCommand("x", panel.x_range.value_or(unit), false),
                    RangeCommand("y", panel.y_range.value_or(unit), false),
                    TicsCommand("x", panel.x_tics), TicsCommand("y", panel.y_tics),
                    "set label 1 'no data' at graph 0.5, graph 0.5 center\n",
                    "plot NaN notitle\n\n");
    return out;
  }
  absl::StrAppend(&out, RangeCommand("x", panel.x_range, true),
                  RangeCommand("y", panel.y_range, false), TicsCommand("x", panel.x_tics),
                  TicsCommand("y", panel.y_tics));
  std::vector<std::string> plots;
  for (size_t l = 0; l < panel.lines.size(); ++l) {
    const ChartLine& line = panel.lines[l];
    if (!HasBand(line) || line.x.empty()) continue;
    const std::string color = line.color.empty() ? SeriesColor(static_cast<int>(l)) : line.color;
    plots.push_back(absl::StrCat("data using 'x':(sel(", p, ", ", l, ", 'y_low')):(sel(", p, ", ",
                                 l, ", 'y_high')) with filledcurves fc rgb '", color,
                                 "' fs transparent solid 0.18 noborder notitle"));
  }
  for (size_t l = 0; l < panel.lines.size(); ++l) {
    const ChartLine& line = panel.lines[l];
    if (line.x.empty()) continue;
    plots.push_back(absl::StrCat("data using 'x':(sel(", p, ", ", l, ", 'y')) ",
                                 LineStyle(line, l), " ",
                                 line.label.empty() ? "notitle"
                                                    : absl::StrCat("title ",
                                                                   GnuplotString(line.label))));
  }
  absl::StrAppend(&out, "plot ", absl::StrJoin(plots, ", \\\n     "), "\n\n");
  return out;
}

// `value` with a k or M suffix: "0", "500", "50k", "1.5M".
std::string CompactNumber(double value) {
  if (std::abs(value) >= 1e6) return absl::StrFormat("%gM", value / 1e6);
  if (std::abs(value) >= 1e3) return absl::StrFormat("%gk", value / 1e3);
  return absl::StrFormat("%g", value);
}

}  // namespace

std::vector<Tic> CompactTics(double max) {
  if (!(max > 0) || !std::isfinite(max)) return {};
  const double power = std::pow(10, std::floor(std::log10(max / 5)));
  double spacing = 10 * power;
  for (const double multiple : {1.0, 2.0, 2.5, 5.0}) {
    if (max / (multiple * power) <= 7) {
      spacing = multiple * power;
      break;
    }
  }
  std::vector<Tic> tics;
  for (int i = 0; i * spacing <= max * (1 + 1e-9); ++i) {
    tics.push_back({.at = i * spacing, .label = CompactNumber(i * spacing)});
  }
  return tics;
}

absl::StatusOr<GnuplotFigure> LineChartFigure(const LineChart& chart) {
  DCS_RETURN_IF_ERROR(CheckChart(chart));
  std::vector<std::string> panels;
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    panels.push_back(PanelScript(chart.panels[p], p));
  }
  return MultiplotFigure(
      chart.name, chart.title, Csv(chart, AnyBand(chart)), chart.columns, chart.panel_width,
      chart.panel_height,
      "# The value of column `c` on the rows of line `l` in panel `p`, else NaN.\n"
      "sel(p, l, c) = (column('panel') == p && column('line') == l) ? column(c) : NaN\n\n",
      panels);
}

}  // namespace dcs::report
