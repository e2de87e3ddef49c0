// Copyright 2026 The DCS Authors.
#include "report/generalization_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "report/line_chart.h"

namespace dcs::report {
namespace {

constexpr int kPanelWidth = 520;
constexpr int kPanelHeight = 400;
// Training contexts on a heatmap: Okabe-Ito vermillion, apart from every viridis colour.
constexpr char kTrainingColor[] = "#D55E00";
constexpr char kSharedPoolColor[] = "#555555";  // grey, as the training range's markers
// Viridis at five stops (its published colour map), for `set palette defined`.
constexpr char kViridis[] =
    "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\n";

bool AllFinite(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

absl::Status CheckMap(const GeneralizationMap& map) {
  DCS_RETURN_IF_ERROR(CheckFigureName(map.name));
  const auto invalid = [&map](absl::string_view why) {
    return absl::InvalidArgumentError(absl::StrCat("generalisation map '", map.name, "': ", why));
  };
  if (map.axes.empty() || map.axes.size() > 2) return invalid("needs one or two axes");
  size_t cells = 1;
  for (const MapAxis& axis : map.axes) {
    if (axis.values.empty() || !AllFinite(axis.values)) {
      return invalid(absl::StrCat("axis '", axis.feature, "' needs finite values"));
    }
    cells *= axis.values.size();
  }
  if (map.policies.empty()) return invalid("needs a policy");
  for (const MapPolicy& policy : map.policies) {
    if (policy.means.size() != cells || policy.stds.size() != cells ||
        policy.training.size() != map.axes.size()) {
      return invalid(absl::StrCat("policy '", policy.label, "' needs ", cells,
                                  " means and stds and a training span per axis"));
    }
    if (!AllFinite(policy.means) || !AllFinite(policy.stds)) {
      return invalid(absl::StrCat("policy '", policy.label, "' has a value that is not finite"));
    }
    for (const TrainingSpan& span : policy.training) {
      if (!std::isfinite(span.low) || !std::isfinite(span.high) || !AllFinite(span.pool)) {
        return invalid(absl::StrCat("policy '", policy.label, "' has a training span that is "
                                    "not finite"));
      }
    }
  }
  return absl::OkStatus();
}

// One feature: a line per policy with its band; its training range's ends as dashed markers
// and its pool as points along the bottom.
absl::StatusOr<GnuplotFigure> LinesFigure(const GeneralizationMap& map) {
  const MapAxis& axis = map.axes[0];
  // The legend above the plot: returns fall off at either end of the axis, where a legend
  // inside would hide them.
  LinePanel panel{
      .x_label = axis.feature, .y_label = map.value_label, .legend = LegendPlace::kAbove};
  double bottom = std::numeric_limits<double>::infinity();
  for (const MapPolicy& policy : map.policies) {
    ChartLine line{.label = policy.label, .x = axis.values, .y = policy.means};
    for (size_t i = 0; i < policy.means.size(); ++i) {
      line.y_low.push_back(policy.means[i] - policy.stds[i]);
      line.y_high.push_back(policy.means[i] + policy.stds[i]);
      bottom = std::min(bottom, line.y_low.back());
    }
    panel.lines.push_back(std::move(line));
  }
  std::set<double> markers;
  // Policies trained on one pool (a sweep's conditions, most often) share its points.
  const bool one_pool = std::all_of(
      map.policies.begin(), map.policies.end(), [&](const MapPolicy& policy) {
        return policy.training[0].pool == map.policies.front().training[0].pool;
      });
  for (size_t p = 0; p < map.policies.size(); ++p) {
    const TrainingSpan& span = map.policies[p].training[0];
    markers.insert(span.low);
    markers.insert(span.high);
    if (span.pool.empty() || (one_pool && p > 0)) continue;
    panel.lines.push_back(
        {.label = one_pool ? std::string("training pool")
                           : absl::StrCat("training pool (", map.policies[p].label, ")"),
         .x = span.pool,
         .y = std::vector<double>(span.pool.size(), bottom),
         .color = one_pool ? std::string(kSharedPoolColor) : SeriesColor(static_cast<int>(p)),
         .points = true});
  }
  panel.x_markers.assign(markers.begin(), markers.end());
  return LineChartFigure({.name = map.name,
                          .title = map.title,
                          .panels = {std::move(panel)},
                          .columns = 1,
                          .panel_width = kPanelWidth + 160,
                          .panel_height = kPanelHeight});
}

// The half-width of a cell along `axis`: half the spacing of its values (0.5 for one value).
double HalfCell(const MapAxis& axis) {
  return axis.values.size() > 1 ? (axis.values[1] - axis.values[0]) / 2 : 0.5;
}

// The training range as a dashed outline: a rectangle when both features were varied, a line
// when one was (gnuplot draws no rectangle of zero height), nothing when neither was (the
// point is drawn).
std::string TrainingRange(const TrainingSpan& x, const TrainingSpan& y) {
  const bool x_varies = x.low < x.high;
  const bool y_varies = y.low < y.high;
  if (!x_varies && !y_varies) return "";
  const std::string from = absl::StrCat(CsvNumber(x.low), ",", CsvNumber(y.low));
  const std::string to = absl::StrCat(CsvNumber(x.high), ",", CsvNumber(y.high));
  const std::string style =
      absl::StrCat(" front lc rgb '", kTrainingColor, "' dashtype 2 linewidth 2\n");
  if (x_varies && y_varies) {
    return absl::StrCat("set object rectangle from ", from, " to ", to,
                        " fillstyle empty border", style);
  }
  return absl::StrCat("set arrow from ", from, " to ", to, " nohead", style);
}

// Two features: a heatmap per policy, each cell a box of its mean's colour; the training
// contexts as a dashed rectangle (a line when one feature is held at a value) and points.
absl::StatusOr<GnuplotFigure> HeatmapsFigure(const GeneralizationMap& map) {
  const MapAxis& x = map.axes[0];
  const MapAxis& y = map.axes[1];
  const size_t cells = x.values.size() * y.values.size();
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  std::string csv = "panel,x,y,mean,std\n";
  for (size_t p = 0; p < map.policies.size(); ++p) {
    const MapPolicy& policy = map.policies[p];
    for (size_t cell = 0; cell < cells; ++cell) {
      absl::StrAppend(&csv, p, ",", CsvNumber(x.values[cell % x.values.size()]), ",",
                      CsvNumber(y.values[cell / x.values.size()]), ",",
                      CsvNumber(policy.means[cell]), ",", CsvNumber(policy.stds[cell]), "\n");
      low = std::min(low, policy.means[cell]);
      high = std::max(high, policy.means[cell]);
    }
  }
  if (!(low < high)) high = low + 1;
  const double dx = HalfCell(x);
  const double dy = HalfCell(y);
  const std::string setup = absl::StrCat(
      kViridis, "set cbrange [", CsvNumber(low), ":", CsvNumber(high), "]\n",
      "set cblabel ", GnuplotString(map.value_label), "\n",
      "set xrange [", CsvNumber(x.values.front() - dx), ":", CsvNumber(x.values.back() + dx),
      "]\n", "set yrange [", CsvNumber(y.values.front() - dy), ":",
      CsvNumber(y.values.back() + dy), "]\n", "set xlabel ", GnuplotString(x.feature), "\n",
      "set ylabel ", GnuplotString(y.feature), "\n", "set grid noxtics noytics\n",
      "set key below\n");
  std::vector<std::string> panels;
  for (size_t p = 0; p < map.policies.size(); ++p) {
    const MapPolicy& policy = map.policies[p];
    const TrainingSpan& sx = policy.training[0];
    const TrainingSpan& sy = policy.training[1];
    std::string points = "x,y\n";  // CSV with a header, as the script reads data
    for (double px : sx.pool.empty() ? std::vector<double>{sx.low} : sx.pool) {
      for (double py : sy.pool.empty() ? std::vector<double>{sy.low} : sy.pool) {
        absl::StrAppend(&points, CsvNumber(px), ",", CsvNumber(py), "\n");
      }
    }
    panels.push_back(absl::StrCat(
        "set title ", GnuplotString(policy.label), "\n", "unset object\n", "unset arrow\n",
        TrainingRange(sx, sy),
        "$training", p, " << EOD\n", points, "EOD\n",
        "plot data every ::", p * cells, "::", (p + 1) * cells - 1, " using 'x':'y':(",
        CsvNumber(dx), "):(", CsvNumber(dy), "):'mean' with boxxyerror",
        " fillstyle solid 1.0 noborder linecolor palette notitle, \\\n",
        "     $training", p, " using 'x':'y' with points pointtype 7 pointsize 1.2",
        " linecolor rgb '", kTrainingColor, "' title 'training contexts'\n"));
  }
  return MultiplotFigure(map.name, map.title, std::move(csv),
                         std::min<int>(static_cast<int>(panels.size()), 3), kPanelWidth,
                         kPanelHeight, setup, panels);
}

}  // namespace

absl::StatusOr<GnuplotFigure> GeneralizationMapFigure(const GeneralizationMap& map) {
  DCS_RETURN_IF_ERROR(CheckMap(map));
  return map.axes.size() == 1 ? LinesFigure(map) : HeatmapsFigure(map);
}

}  // namespace dcs::report
