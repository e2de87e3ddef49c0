// Copyright 2026 The DCS Authors.
#include "coordinator/line_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace dcs::coordinator {
namespace {

// Okabe & Ito (2008), ordered so that the first colours are the most distinct on white; the
// yellow, hard to see on white, comes last.
constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#E69F00",
                                    "#CC79A7", "#56B4E9", "#000000", "#F0E442"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

constexpr int kMinPanelWidth = 120;
constexpr int kMinPanelHeight = 100;

// Font sizes in px.
constexpr double kFigureTitleFont = 16;
constexpr double kPanelTitleFont = 13;
constexpr double kAxisLabelFont = 11.5;
constexpr double kTickFont = 10.5;
constexpr double kLegendFont = 11;
// Estimated advance of one character, in em: a little above the average of Helvetica and
// Arial, so that estimated widths err on the wide side.
constexpr double kCharEm = 0.6;

// Layout, in px.
constexpr double kFigureMargin = 8;       // left and right of the panel grid
constexpr double kFigureTitleBand = 36;   // height of the figure title band
constexpr double kFigureBottom = 8;       // below the last row of panels
constexpr double kPanelTitleBand = 24;    // panel top to the legend (or plot) with a title
constexpr double kPanelTopNoTitle = 8;    // the same without a title
constexpr double kLegendRow = 16;         // height of one legend row
constexpr double kLegendSwatch = 18;      // length of a legend's line sample
constexpr double kLegendGap = 12;         // between legend items
constexpr double kPlotTopGap = 8;         // legend (or title band) to the plot area
constexpr double kTickLength = 4;
constexpr double kTickLabelGap = 3;       // tick mark to its label
constexpr double kYLabelBand = 20;        // left of the y tick labels, for the y axis label
constexpr int kMaxLegendRows = 3;
// The legend shrinks the plot no further than to this share of the panel's height and px.
constexpr double kMinPlotHeightShare = 0.35;
constexpr double kMinPlotHeight = 40;
constexpr int kMaxTicks = 12;             // per axis, when there is room
constexpr double kMinTickLabelGap = 10;   // between x tick labels
constexpr double kMinYTickSpacing = 18;   // between y ticks
constexpr double kLineWidth = 1.25;
constexpr double kMaxPixel = 1e6;         // coordinates are clamped to +-this (they are clipped)

constexpr double kTiny = 1e-200;          // data spans below this count as constant

constexpr absl::string_view kEllipsis = "\xE2\x80\xA6";  // U+2026

// `value` with `decimals` digits after the point, trailing zeros (and point) removed, and no
// negative zero.
std::string FormatFixed(double value, int decimals) {
  char buffer[96];
  int n = std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, value);
  std::string text(buffer, std::clamp(n, 0, static_cast<int>(sizeof(buffer)) - 1));
  if (text.find('.') != std::string::npos) {
    while (!text.empty() && text.back() == '0') text.pop_back();
    if (!text.empty() && text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

// `value` with three significant digits in the shortest of %f and %e notation.
std::string FormatShort(double value) {
  char buffer[64];
  int n = std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  std::string text(buffer, std::clamp(n, 0, static_cast<int>(sizeof(buffer)) - 1));
  if (text == "-0") text = "0";
  return text;
}

// A pixel coordinate rounded to 0.1 px.
std::string Px(double value) {
  return FormatFixed(std::clamp(value, -kMaxPixel, kMaxPixel), 1);
}

// Characters (code points) of UTF-8 `text`.
int CodePoints(absl::string_view text) {
  int count = 0;
  for (char c : text) {
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++count;
  }
  return count;
}

double TextWidth(absl::string_view text, double font_px) {
  return CodePoints(text) * font_px * kCharEm;
}

// `text`, cut at a character boundary and ended with an ellipsis if it is estimated wider than
// `max_px`.
std::string Ellipsize(absl::string_view text, double max_px, double font_px) {
  if (TextWidth(text, font_px) <= max_px) return std::string(text);
  const int keep = static_cast<int>(std::floor(max_px / (font_px * kCharEm))) - 1;
  if (keep < 1) return "";
  int seen = 0;
  size_t end = 0;
  for (; end < text.size(); ++end) {
    if ((static_cast<unsigned char>(text[end]) & 0xC0) != 0x80) {
      if (seen == keep) break;
      ++seen;
    }
  }
  return absl::StrCat(text.substr(0, end), kEllipsis);
}

// `text` escaped for XML character data and attribute values. Control characters, which XML
// 1.0 does not allow, become spaces.
std::string Escape(absl::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\t': case '\n': case '\r': out += ' '; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += ' ';
        } else {
          out += c;
        }
    }
  }
  return out;
}

// Text element: `anchor` is start, middle or end; `extra` holds more attributes.
void AppendText(std::string& out, double x, double y, double font_px, absl::string_view anchor,
                absl::string_view fill, absl::string_view extra, absl::string_view text) {
  absl::StrAppend(&out, "<text x=\"", Px(x), "\" y=\"", Px(y), "\" font-size=\"",
                  FormatFixed(font_px, 1), "\" text-anchor=\"", anchor, "\" fill=\"", fill, "\"",
                  extra, ">", Escape(text), "</text>\n");
}

std::string DescribeSeries(int panel, const Panel& p, int series, const Series& s) {
  return absl::StrCat("panel ", panel, " (\"", p.title, "\"), series ", series, " (\"", s.label,
                      "\")");
}

absl::Status CheckRange(const std::optional<std::pair<double, double>>& range,
                        absl::string_view axis, int panel, const Panel& p) {
  if (!range.has_value()) return absl::OkStatus();
  const auto [lo, hi] = *range;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || !std::isfinite(hi - lo)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "panel ", panel, " (\"", p.title, "\"): ", axis, "_range must be finite with min < max",
        " and a finite span, got [", FormatShort(lo), ", ", FormatShort(hi), "]"));
  }
  return absl::OkStatus();
}

absl::Status Validate(const Figure& figure) {
  if (figure.columns < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("figure columns must be at least 1, got ", figure.columns));
  }
  if (figure.panel_width < kMinPanelWidth || figure.panel_height < kMinPanelHeight) {
    return absl::InvalidArgumentError(absl::StrCat(
        "panels must be at least ", kMinPanelWidth, "x", kMinPanelHeight, " px, got ",
        figure.panel_width, "x", figure.panel_height));
  }
  for (int i = 0; i < static_cast<int>(figure.panels.size()); ++i) {
    const Panel& p = figure.panels[i];
    if (absl::Status s = CheckRange(p.x_range, "x", i, p); !s.ok()) return s;
    if (absl::Status s = CheckRange(p.y_range, "y", i, p); !s.ok()) return s;
    for (const std::vector<double>* markers : {&p.x_markers, &p.y_markers}) {
      for (double marker : *markers) {
        if (!std::isfinite(marker)) {
          return absl::InvalidArgumentError(absl::StrCat(
              "panel ", i, " (\"", p.title, "\"): ", markers == &p.x_markers ? "x" : "y",
              " marker ", FormatShort(marker), " is not finite"));
        }
      }
    }
    for (int j = 0; j < static_cast<int>(p.series.size()); ++j) {
      const Series& s = p.series[j];
      if (s.x.size() != s.y.size()) {
        return absl::InvalidArgumentError(
            absl::StrCat(DescribeSeries(i, p, j, s), ": x has ", s.x.size(),
                         " values but y has ", s.y.size()));
      }
      for (size_t k = 0; k < s.x.size(); ++k) {
        if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) {
          return absl::InvalidArgumentError(
              absl::StrCat(DescribeSeries(i, p, j, s), ": point ", k,
                           " is not finite (NaN or infinite)"));
        }
      }
    }
  }
  return absl::OkStatus();
}

// The span of an axis: the fixed range, or the data's with `margin` (a share of the span) on
// each side. A constant or empty axis gets a span around its value.
absl::StatusOr<std::pair<double, double>> AxisSpan(
    const std::optional<std::pair<double, double>>& fixed, const std::vector<double>& values,
    double margin, absl::string_view axis, int panel) {
  if (fixed.has_value()) return *fixed;
  if (values.empty()) return std::pair<double, double>(0.0, 1.0);
  const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
  double lo = *min_it;
  double hi = *max_it;
  const double magnitude = std::max(std::fabs(lo), std::fabs(hi));
  if (hi - lo <= std::max(1e-9 * magnitude, kTiny)) {  // constant, up to rounding
    const double center = lo / 2 + hi / 2;
    if (std::fabs(center) <= kTiny) return std::pair<double, double>(-1.0, 1.0);
    const double half = std::fabs(center) * 0.1;
    lo = center - half;
    hi = center + half;
  } else {
    const double span = hi - lo;
    lo -= margin * span;
    hi += margin * span;
  }
  if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "panel ", panel, ": the ", axis, " values span more than the largest double"));
  }
  return std::pair<double, double>(lo, hi);
}

struct Axis {
  double lo = 0;
  double hi = 1;
  std::vector<double> ticks;
  std::vector<std::string> labels;
};

// Tick labels in one format for the whole axis: as many decimals as the step needs, a k/M/G
// suffix for large values, %g for extreme ones.
std::vector<std::string> TickLabels(const std::vector<double>& ticks, double step) {
  double max_abs = 0;
  for (double t : ticks) max_abs = std::max(max_abs, std::fabs(t));
  std::vector<std::string> labels;
  labels.reserve(ticks.size());
  if (max_abs >= 1e15 || (max_abs > 0 && max_abs < 1e-4)) {
    for (double t : ticks) labels.push_back(FormatShort(t));
    return labels;
  }
  double scale = 1;
  absl::string_view suffix;
  if (max_abs >= 1e9) {
    scale = 1e9;
    suffix = "G";
  } else if (max_abs >= 1e6) {
    scale = 1e6;
    suffix = "M";
  } else if (max_abs >= 1e4) {
    scale = 1e3;
    suffix = "k";
  }
  const double scaled_step = step / scale;
  int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(scaled_step) - 1e-9)));
  while (decimals < 12) {
    const double shifted = scaled_step * std::pow(10.0, decimals);
    if (std::fabs(shifted - std::round(shifted)) <= 1e-6 * shifted) break;
    ++decimals;
  }
  for (double t : ticks) {
    std::string label = FormatFixed(t / scale, decimals);
    if (label != "0") absl::StrAppend(&label, suffix);
    labels.push_back(std::move(label));
  }
  return labels;
}

// "Nice" ticks inside [lo, hi]: multiples of 1, 2 or 5 times a power of ten, 4 to 6 of them
// (5 preferred, then fewer); 2.5 times a power of ten only if no other step gives 4 to 6. At
// most `max_ticks` (>= 2), which also lowers the 4-to-6 target.
Axis MakeAxis(double lo, double hi, int max_ticks) {
  Axis axis{.lo = lo, .hi = hi};
  const double span = hi - lo;
  const double power = std::floor(std::log10(span));
  const double fewest = std::min(4, max_ticks);
  const double most = std::min(6, max_ticks);
  const double ideal = std::min(5, max_ticks);
  double best_score = std::numeric_limits<double>::infinity();
  double best_step = 0;
  int64_t best_first = 0;
  int64_t best_last = -1;
  for (double exponent : {power - 1, power, power + 1}) {
    const double magnitude = std::pow(10.0, exponent);
    for (double multiple : {1.0, 2.0, 2.5, 5.0}) {
      const double step = multiple * magnitude;
      if (!(step > 0) || !std::isfinite(step)) continue;
      const double first = std::ceil(lo / step - 1e-9);
      const double last = std::floor(hi / step + 1e-9);
      const double count = last - first + 1;
      // Not in [0, max_ticks] also when the span is at the limit of double precision.
      if (!(count >= 0 && count <= max_ticks)) continue;
      const double outside = count < fewest ? fewest - count : (count > most ? count - most : 0);
      const double score = outside * 100 + (multiple == 2.5 ? 10 : 0) +
                           std::fabs(count - ideal) + (count > ideal ? 0.5 : 0);
      if (score < best_score) {
        best_score = score;
        best_step = step;
        best_first = static_cast<int64_t>(first);
        best_last = static_cast<int64_t>(last);
      }
    }
  }
  for (int64_t i = best_first; i <= best_last; ++i) {
    axis.ticks.push_back(static_cast<double>(i) * best_step);
  }
  if (!axis.ticks.empty()) axis.labels = TickLabels(axis.ticks, best_step);
  return axis;
}

struct LegendItem {
  int series;        // index, for the colour
  std::string text;  // already ellipsized; "+N more" has series -1
  double x;          // relative to the plot's left edge
  int row;
};

// Lays out the labelled series of `panel` in at most `max_rows` rows of `width` px.
std::vector<LegendItem> LayOutLegend(const Panel& panel, double width, int max_rows) {
  std::vector<LegendItem> items;
  int labelled = 0;
  for (const Series& s : panel.series) labelled += s.label.empty() ? 0 : 1;
  if (labelled == 0 || max_rows < 1) return items;
  const double text_room = width - kLegendSwatch - 4;
  double x = 0;
  int row = 0;
  for (int i = 0; i < static_cast<int>(panel.series.size()); ++i) {
    if (panel.series[i].label.empty()) continue;
    std::string text = Ellipsize(panel.series[i].label, text_room, kLegendFont);
    const double item_width = kLegendSwatch + 4 + TextWidth(text, kLegendFont);
    if (x > 0 && x + item_width > width) {
      ++row;
      x = 0;
    }
    if (row >= max_rows) break;
    items.push_back({.series = i, .text = std::move(text), .x = x, .row = row});
    x += item_width + kLegendGap;
  }
  const int hidden = labelled - static_cast<int>(items.size());
  if (hidden > 0) {
    // Make room on the last row for a note of how many are not shown.
    int shown_hidden = hidden;
    while (true) {
      const std::string note = absl::StrCat("+", shown_hidden, " more");
      double end = 0;
      int note_row = 0;
      if (!items.empty()) {
        const LegendItem& last = items.back();
        end = last.x + kLegendSwatch + 4 + TextWidth(last.text, kLegendFont) + kLegendGap;
        note_row = last.row;
      }
      if (items.empty() || end + TextWidth(note, kLegendFont) <= width) {
        items.push_back({.series = -1, .text = note, .x = end, .row = note_row});
        break;
      }
      items.pop_back();
      ++shown_hidden;
    }
  }
  return items;
}

// Where the parts of a panel go, in the panel's coordinates.
struct PanelLayout {
  double plot_left, plot_right, plot_top, plot_bottom;
  double title_band;
  std::vector<LegendItem> legend;
};

PanelLayout LayOutPanel(const Panel& panel, const Axis& x_axis, const Axis& y_axis, double width,
                        double height) {
  PanelLayout layout;
  // Horizontal: y tick labels (and the y axis label) on the left; room for half of the last x
  // tick label on the right.
  double y_tick_width = 0;
  for (const std::string& label : y_axis.labels) {
    y_tick_width = std::max(y_tick_width, TextWidth(label, kTickFont));
  }
  const double first_x_half =
      x_axis.labels.empty() ? 0 : TextWidth(x_axis.labels.front(), kTickFont) / 2;
  const double last_x_half =
      x_axis.labels.empty() ? 0 : TextWidth(x_axis.labels.back(), kTickFont) / 2;
  layout.plot_left = std::round(std::max(
      (panel.y_label.empty() ? 6 : kYLabelBand) + y_tick_width + kTickLength + kTickLabelGap,
      first_x_half + 6));
  layout.plot_right = std::round(width - std::max(12.0, last_x_half + 4));

  // Vertical: title, legend rows, plot, x tick labels, x axis label.
  layout.title_band = panel.title.empty() ? kPanelTopNoTitle : kPanelTitleBand;
  const double bottom_band = panel.x_label.empty() ? 22 : 40;
  const double room_for_legend = height - layout.title_band - kPlotTopGap - bottom_band -
                                 std::max(kMinPlotHeight, kMinPlotHeightShare * height);
  const int max_rows = std::clamp(static_cast<int>(std::floor(room_for_legend / kLegendRow)), 0,
                                  kMaxLegendRows);
  layout.legend = LayOutLegend(panel, layout.plot_right - layout.plot_left, max_rows);
  const int legend_rows = layout.legend.empty() ? 0 : layout.legend.back().row + 1;
  layout.plot_top = layout.title_band + legend_rows * kLegendRow + kPlotTopGap;
  layout.plot_bottom = std::round(height - bottom_band);
  return layout;
}

// Appends one panel, whose top-left corner is at (left, top) in the figure, with axes spanning
// `x_span` and `y_span`.
void AppendPanel(std::string& out, int index, const Panel& panel,
                 std::pair<double, double> x_span, std::pair<double, double> y_span,
                 double left, double top, double width, double height) {
  // Ticks close enough for their labels to touch are thinned out, which can change the layout.
  Axis x_axis = MakeAxis(x_span.first, x_span.second, kMaxTicks);
  Axis y_axis = MakeAxis(y_span.first, y_span.second, kMaxTicks);
  PanelLayout layout;
  for (int pass = 0;; ++pass) {
    layout = LayOutPanel(panel, x_axis, y_axis, width, height);
    if (pass == 2) break;
    double x_label_width = 0;
    for (const std::string& label : x_axis.labels) {
      x_label_width = std::max(x_label_width, TextWidth(label, kTickFont));
    }
    const int x_max = std::max(2, 1 + static_cast<int>((layout.plot_right - layout.plot_left) /
                                                       (x_label_width + kMinTickLabelGap)));
    const int y_max = std::max(
        2, 1 + static_cast<int>((layout.plot_bottom - layout.plot_top) / kMinYTickSpacing));
    const bool thin_x = static_cast<int>(x_axis.ticks.size()) > x_max;
    const bool thin_y = static_cast<int>(y_axis.ticks.size()) > y_max;
    if (thin_x) x_axis = MakeAxis(x_span.first, x_span.second, x_max);
    if (thin_y) y_axis = MakeAxis(y_span.first, y_span.second, y_max);
    if (!thin_x && !thin_y) break;
  }
  const double plot_left = layout.plot_left;
  const double plot_right = layout.plot_right;
  const double plot_top = layout.plot_top;
  const double plot_bottom = layout.plot_bottom;
  const double plot_width = plot_right - plot_left;
  const double plot_height = plot_bottom - plot_top;
  const double title_band = layout.title_band;
  const std::vector<LegendItem>& legend = layout.legend;

  auto to_x = [&](double x) {
    return plot_left + (x - x_axis.lo) / (x_axis.hi - x_axis.lo) * plot_width;
  };
  auto to_y = [&](double y) {
    return plot_bottom - (y - y_axis.lo) / (y_axis.hi - y_axis.lo) * plot_height;
  };

  const std::string clip_id = absl::StrCat("dcs-clip-", index);
  absl::StrAppend(&out, "<g class=\"panel\" id=\"panel-", index, "\" transform=\"translate(",
                  Px(left), ",", Px(top), ")\">\n");
  // Lines may reach a little past the plot area, so that a line along an edge is not cut in
  // half.
  const double clip_pad = 2 * kLineWidth;
  absl::StrAppend(&out, "<defs><clipPath id=\"", clip_id, "\"><rect x=\"",
                  Px(plot_left - clip_pad), "\" y=\"", Px(plot_top - clip_pad), "\" width=\"",
                  Px(plot_width + 2 * clip_pad), "\" height=\"", Px(plot_height + 2 * clip_pad),
                  "\"/></clipPath></defs>\n");

  // Grid lines and tick marks.
  std::string grid;
  std::string zero;
  std::string marks;
  for (double t : x_axis.ticks) {
    const std::string x = Px(to_x(t));
    absl::StrAppend(&grid, "M", x, " ", Px(plot_top), "V", Px(plot_bottom));
    absl::StrAppend(&marks, "M", x, " ", Px(plot_bottom), "v", Px(kTickLength));
  }
  for (double t : y_axis.ticks) {
    const std::string y = Px(to_y(t));
    absl::StrAppend(t == 0 ? &zero : &grid, "M", Px(plot_left), " ", y, "H", Px(plot_right));
    absl::StrAppend(&marks, "M", Px(plot_left), " ", y, "h", Px(-kTickLength));
  }
  if (!grid.empty()) {
    absl::StrAppend(&out, "<path class=\"grid\" d=\"", grid,
                    "\" stroke=\"#e6e6e6\" stroke-width=\"1\" fill=\"none\"/>\n");
  }
  if (!zero.empty()) {
    absl::StrAppend(&out, "<path class=\"zero\" d=\"", zero,
                    "\" stroke=\"#c4c4c4\" stroke-width=\"1\" fill=\"none\"/>\n");
  }

  // Reference lines.
  std::string x_markers;
  for (double m : panel.x_markers) {
    if (m < x_axis.lo || m > x_axis.hi) continue;
    absl::StrAppend(&x_markers, "M", Px(to_x(m)), " ", Px(plot_top), "V", Px(plot_bottom));
  }
  if (!x_markers.empty()) {
    absl::StrAppend(&out, "<path class=\"x-marker\" d=\"", x_markers,
                    "\" stroke=\"#8c8c8c\" stroke-width=\"1\" stroke-dasharray=\"4 3\"",
                    " fill=\"none\"/>\n");
  }
  std::string y_markers;
  for (double m : panel.y_markers) {
    if (m < y_axis.lo || m > y_axis.hi) continue;
    absl::StrAppend(&y_markers, "M", Px(plot_left), " ", Px(to_y(m)), "H", Px(plot_right));
  }
  if (!y_markers.empty()) {
    absl::StrAppend(&out, "<path class=\"y-marker\" d=\"", y_markers,
                    "\" stroke=\"#8c8c8c\" stroke-width=\"1\" stroke-dasharray=\"1 3\"",
                    " fill=\"none\"/>\n");
  }

  // Series.
  absl::StrAppend(&out, "<g clip-path=\"url(#", clip_id, ")\" fill=\"none\" stroke-width=\"",
                  FormatFixed(kLineWidth, 2),
                  "\" stroke-linejoin=\"round\" stroke-linecap=\"round\">\n");
  for (int i = 0; i < static_cast<int>(panel.series.size()); ++i) {
    const Series& s = panel.series[i];
    const char* colour = kPalette[i % kPaletteSize];
    std::string points;
    points.reserve(s.x.size() * 12);
    for (size_t k = 0; k < s.x.size(); ++k) {
      absl::StrAppend(&points, k == 0 ? "" : " ", Px(to_x(s.x[k])), ",", Px(to_y(s.y[k])));
    }
    absl::StrAppend(&out, "<polyline class=\"series\" points=\"", points, "\" stroke=\"", colour,
                    "\">");
    if (!s.label.empty()) absl::StrAppend(&out, "<title>", Escape(s.label), "</title>");
    absl::StrAppend(&out, "</polyline>\n");
    if (s.x.size() == 1) {  // a polyline of one point draws nothing
      absl::StrAppend(&out, "<circle cx=\"", Px(to_x(s.x[0])), "\" cy=\"", Px(to_y(s.y[0])),
                      "\" r=\"2.5\" fill=\"", colour, "\" stroke=\"none\"/>\n");
    }
  }
  absl::StrAppend(&out, "</g>\n");

  // Frame and ticks on top of the lines.
  absl::StrAppend(&out, "<rect class=\"plot-area\" x=\"", Px(plot_left), "\" y=\"",
                  Px(plot_top), "\" width=\"", Px(plot_width), "\" height=\"", Px(plot_height),
                  "\" fill=\"none\" stroke=\"#8c8c8c\" stroke-width=\"1\"/>\n");
  if (!marks.empty()) {
    absl::StrAppend(&out, "<path class=\"ticks\" d=\"", marks,
                    "\" stroke=\"#8c8c8c\" stroke-width=\"1\" fill=\"none\"/>\n");
  }
  for (size_t k = 0; k < x_axis.ticks.size(); ++k) {
    AppendText(out, to_x(x_axis.ticks[k]), plot_bottom + kTickLength + kTickLabelGap + 8,
               kTickFont, "middle", "#555555", " class=\"tick-label x\"", x_axis.labels[k]);
  }
  for (size_t k = 0; k < y_axis.ticks.size(); ++k) {
    AppendText(out, plot_left - kTickLength - kTickLabelGap, to_y(y_axis.ticks[k]) + 3.5,
               kTickFont, "end", "#555555", " class=\"tick-label y\"", y_axis.labels[k]);
  }

  // Axis labels and title.
  const double plot_center_x = plot_left + plot_width / 2;
  if (!panel.x_label.empty()) {
    AppendText(out, plot_center_x, plot_bottom + 33, kAxisLabelFont, "middle", "#333333",
               " class=\"axis-label x\"",
               Ellipsize(panel.x_label, plot_width + 2 * std::min(plot_left, width - plot_right),
                         kAxisLabelFont));
  }
  if (!panel.y_label.empty()) {
    const double center_y = plot_top + plot_height / 2;
    // The band left of the tick labels is free from below the title to the panel's bottom.
    const double room = 2 * std::min(center_y - title_band, height - 4 - center_y);
    // Rotated -90 degrees about the origin: x runs up the panel, y to the right.
    AppendText(out, -center_y, 13, kAxisLabelFont, "middle", "#333333",
               " class=\"axis-label y\" transform=\"rotate(-90)\"",
               Ellipsize(panel.y_label, room, kAxisLabelFont));
  }
  if (!panel.title.empty()) {
    const double room = 2 * std::min(plot_center_x - 4, width - 4 - plot_center_x);
    AppendText(out, plot_center_x, 17, kPanelTitleFont, "middle", "#222222",
               " class=\"panel-title\" font-weight=\"600\"",
               Ellipsize(panel.title, room, kPanelTitleFont));
  }

  // Legend, between the title and the plot.
  if (!legend.empty()) {
    absl::StrAppend(&out, "<g class=\"legend\">\n");
    for (const LegendItem& item : legend) {
      const double row_top = title_band + item.row * kLegendRow;
      double x = plot_left + item.x;
      if (item.series >= 0) {
        const double y = row_top + 8;
        absl::StrAppend(&out, "<path d=\"M", Px(x), " ", Px(y), "h", Px(kLegendSwatch),
                        "\" stroke=\"", kPalette[item.series % kPaletteSize],
                        "\" stroke-width=\"2\" fill=\"none\"/>\n");
        x += kLegendSwatch + 4;
      }
      AppendText(out, x, row_top + 12, kLegendFont, "start",
                 item.series >= 0 ? "#333333" : "#777777", "", item.text);
    }
    absl::StrAppend(&out, "</g>\n");
  }
  absl::StrAppend(&out, "</g>\n");
}

}  // namespace

absl::StatusOr<std::string> RenderSvg(const Figure& figure) {
  if (absl::Status status = Validate(figure); !status.ok()) return status;

  // Every panel's axes first, so that a bad axis fails before any output.
  std::vector<std::pair<std::pair<double, double>, std::pair<double, double>>> spans;
  spans.reserve(figure.panels.size());
  for (int i = 0; i < static_cast<int>(figure.panels.size()); ++i) {
    const Panel& panel = figure.panels[i];
    std::vector<double> xs;
    std::vector<double> ys;
    for (const Series& s : panel.series) {
      xs.insert(xs.end(), s.x.begin(), s.x.end());
      ys.insert(ys.end(), s.y.begin(), s.y.end());
    }
    absl::StatusOr<std::pair<double, double>> x_span = AxisSpan(panel.x_range, xs, 0.0, "x", i);
    if (!x_span.ok()) return x_span.status();
    absl::StatusOr<std::pair<double, double>> y_span = AxisSpan(panel.y_range, ys, 0.05, "y", i);
    if (!y_span.ok()) return y_span.status();
    spans.emplace_back(*x_span, *y_span);
  }

  const int count = static_cast<int>(figure.panels.size());
  const int columns = std::max(1, std::min(figure.columns, count));
  const int rows = (count + columns - 1) / columns;
  const double title_band = figure.title.empty() ? kFigureBottom : kFigureTitleBand;
  const double width = 2 * kFigureMargin + static_cast<double>(columns) * figure.panel_width;
  const double height =
      title_band + static_cast<double>(rows) * figure.panel_height + kFigureBottom;

  std::string out;
  out.reserve(4096 + figure.panels.size() * 4096);
  absl::StrAppend(&out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n",
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"",
                  Px(width), "\" height=\"", Px(height), "\" viewBox=\"0 0 ", Px(width), " ",
                  Px(height), "\" font-family=\"Helvetica, Arial, sans-serif\">\n");
  absl::StrAppend(&out, "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
  if (!figure.title.empty()) {
    absl::StrAppend(&out, "<title>", Escape(figure.title), "</title>\n");
    AppendText(out, width / 2, 24, kFigureTitleFont, "middle", "#111111",
               " class=\"figure-title\" font-weight=\"600\"",
               Ellipsize(figure.title, width - 2 * kFigureMargin, kFigureTitleFont));
  }
  for (int i = 0; i < count; ++i) {
    const double left = kFigureMargin + static_cast<double>(i % columns) * figure.panel_width;
    const double top = title_band + static_cast<double>(i / columns) * figure.panel_height;
    AppendPanel(out, i, figure.panels[i], spans[i].first, spans[i].second, left, top,
                figure.panel_width, figure.panel_height);
  }
  absl::StrAppend(&out, "</svg>\n");
  return out;
}

}  // namespace dcs::coordinator
