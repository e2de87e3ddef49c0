// Copyright 2026 The DCS Authors.
#include "report/bar_chart.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::report {
namespace {

constexpr double kGroupGap = 0.6;   // extra space between groups, in category widths
constexpr double kClusterWidth = 0.8;  // of a category's width, for its bars together

absl::Status CheckSeries(const BarSeries& series, size_t categories, const std::string& where) {
  const bool has_errors = !series.y_low.empty() || !series.y_high.empty();
  if (series.y.size() != categories ||
      (has_errors && (series.y_low.size() != categories || series.y_high.size() != categories))) {
    return absl::InvalidArgumentError(absl::StrCat(
        where, ": needs a value (and error bars) per category: ", categories, " categories, ",
        series.y.size(), " values, ", series.y_low.size(), " and ", series.y_high.size(),
        " error bar ends"));
  }
  for (size_t i = 0; i < categories; ++i) {
    if (std::isinf(series.y[i]) ||
        (has_errors && !std::isnan(series.y[i]) &&
         (!std::isfinite(series.y_low[i]) || !std::isfinite(series.y_high[i])))) {
      return absl::InvalidArgumentError(
          absl::StrCat(where, ", category ", i, ": values and error bars must be finite"));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckChart(const BarChart& chart) {
  DCS_RETURN_IF_ERROR(CheckPanelGrid("bar chart", chart.name, chart.panels.size(),
                                     chart.columns, chart.panel_width, chart.panel_height));
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    const BarPanel& panel = chart.panels[p];
    for (size_t s = 0; s < panel.series.size(); ++s) {
      DCS_RETURN_IF_ERROR(
          CheckSeries(panel.series[s], panel.categories.size(),
                      absl::StrCat("bar chart '", chart.name, "', panel ", p, ", series ", s)));
    }
  }
  return absl::OkStatus();
}

// Where each category's cluster is centred: one unit apart, plus a gap where the group changes.
std::vector<double> CategoryCentres(const BarPanel& panel) {
  std::vector<double> centres;
  double x = 0;
  for (size_t i = 0; i < panel.categories.size(); ++i) {
    if (i > 0) x += panel.categories[i].group == panel.categories[i - 1].group ? 1 : 1 + kGroupGap;
    centres.push_back(x);
  }
  return centres;
}

double BarWidth(const BarPanel& panel) {
  return kClusterWidth / static_cast<double>(std::max<size_t>(panel.series.size(), 1));
}

double BarCentre(const BarPanel& panel, const std::vector<double>& centres, size_t category,
                 size_t series) {
  return centres[category] - kClusterWidth / 2 + BarWidth(panel) * (series + 0.5);
}

bool HasErrors(const BarSeries& series) { return !series.y_low.empty(); }

std::string Csv(const BarChart& chart) {
  std::string csv =
      "panel,series,category,x,y,y_low,y_high,group,category_label,label\n";
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    const BarPanel& panel = chart.panels[p];
    const std::vector<double> centres = CategoryCentres(panel);
    for (size_t s = 0; s < panel.series.size(); ++s) {
      const BarSeries& series = panel.series[s];
      for (size_t c = 0; c < panel.categories.size(); ++c) {
        if (std::isnan(series.y[c])) continue;
        absl::StrAppend(&csv, p, ",", s, ",", c, ",", CsvNumber(BarCentre(panel, centres, c, s)),
                        ",", CsvNumber(series.y[c]), ",");
        if (HasErrors(series)) {
          absl::StrAppend(&csv, CsvNumber(series.y_low[c]), ",", CsvNumber(series.y_high[c]));
        } else {
          absl::StrAppend(&csv, ",");
        }
        absl::StrAppend(&csv, ",", CsvField(panel.categories[c].group), ",",
                        CsvField(panel.categories[c].label), ",", CsvField(series.label), "\n");
      }
    }
  }
  return csv;
}

// The y axis: the bars, their error bars and 0, 3% below, 16% above for the group names.
std::pair<double, double> YRange(const BarPanel& panel) {
  double lo = 0;
  double hi = 0;
  for (const BarSeries& series : panel.series) {
    for (size_t c = 0; c < series.y.size(); ++c) {
      if (std::isnan(series.y[c])) continue;
      lo = std::min(lo, series.y[c]);
      hi = std::max(hi, series.y[c]);
      if (HasErrors(series)) {
        lo = std::min({lo, series.y_low[c], series.y_high[c]});
        hi = std::max({hi, series.y_low[c], series.y_high[c]});
      }
    }
  }
  const double span = hi > lo ? hi - lo : 1;
  return {lo < 0 ? lo - 0.03 * span : 0, hi + 0.16 * span};
}

bool HasBars(const BarPanel& panel) {
  for (const BarSeries& series : panel.series) {
    if (std::any_of(series.y.begin(), series.y.end(), [](double y) { return !std::isnan(y); })) {
      return true;
    }
  }
  return false;
}

// Group names above their clusters, and dotted lines between groups.
std::string GroupMarks(const BarPanel& panel, const std::vector<double>& centres) {
  std::string out;
  size_t begin = 0;
  for (size_t i = 1; i <= panel.categories.size(); ++i) {
    if (i < panel.categories.size() && panel.categories[i].group == panel.categories[begin].group) {
      continue;
    }
    if (!panel.categories[begin].group.empty()) {
      absl::StrAppend(&out, "set label ", GnuplotString(panel.categories[begin].group),
                      " at first ", CsvNumber((centres[begin] + centres[i - 1]) / 2),
                      ", graph 0.95 center textcolor rgb '#333333'\n");
    }
    if (i < panel.categories.size()) {
      absl::StrAppend(&out, "set arrow from first ",
                      CsvNumber((centres[i - 1] + centres[i]) / 2), ", graph 0 to first ",
                      CsvNumber((centres[i - 1] + centres[i]) / 2),
                      ", graph 1 nohead back lc rgb '#8c8c8c' dt 3\n");
    }
    begin = i;
  }
  return out;
}

std::string PanelScript(const BarPanel& panel, size_t p) {
  std::string out = absl::StrCat("# Panel ", p, "\n", "set title ", GnuplotString(panel.title),
                                 " font sprintf(',%d', fontsize + 1)\n",
                                 "set xlabel ", GnuplotString(panel.x_label), "\n",
                                 "set ylabel ", GnuplotString(panel.y_label), "\n",
                                 "unset arrow\nunset label\n");
  if (!HasBars(panel)) {
    absl::StrAppend(&out, "unset key\nset xtics autofreq\nset xrange [0:1]\nset yrange [0:1]\n",
                    "set label 1 'no data' at graph 0.5, graph 0.5 center\n",
                    "plot NaN notitle\n\n");
    return out;
  }
  const std::vector<double> centres = CategoryCentres(panel);
  std::vector<std::string> tics;
  for (size_t c = 0; c < panel.categories.size(); ++c) {
    tics.push_back(absl::StrCat(GnuplotString(panel.categories[c].label), " ",
                                CsvNumber(centres[c])));
  }
  const std::pair<double, double> y = YRange(panel);
  absl::StrAppend(&out, KeyCommand(panel.legend), "set xtics (", absl::StrJoin(tics, ", "), ")",
                  panel.categories.size() > 12 ? " rotate by 45 right" : "", "\n",
                  "set xrange [", CsvNumber(centres.front() - 0.6), ":",
                  CsvNumber(centres.back() + 0.6), "]\n", "set yrange [", CsvNumber(y.first),
                  ":", CsvNumber(y.second), "]\n", GroupMarks(panel, centres));
  if (y.first < 0) {
    absl::StrAppend(&out, "set arrow from graph 0, first 0 to graph 1, first 0 nohead ",
                    "lc rgb '#555555'\n");
  }
  std::vector<std::string> plots;
  for (size_t s = 0; s < panel.series.size(); ++s) {
    const BarSeries& series = panel.series[s];
    const std::string color =
        series.color.empty() ? SeriesColor(static_cast<int>(s)) : series.color;
    plots.push_back(absl::StrCat(
        "data using 'x':(sel(", p, ", ", s, ", 'y')):(", CsvNumber(BarWidth(panel) * 0.92),
        ") with boxes fc rgb '", color, "' fs solid 0.85 noborder ",
        series.label.empty() ? "notitle" : absl::StrCat("title ", GnuplotString(series.label))));
  }
  for (size_t s = 0; s < panel.series.size(); ++s) {
    if (!HasErrors(panel.series[s])) continue;
    // A plain vertical line from y_low to y_high (no caps, no point).
    plots.push_back(absl::StrCat("data using 'x':(sel(", p, ", ", s, ", 'y_low')):(0):(sel(", p,
                                 ", ", s, ", 'y_high') - sel(", p, ", ", s,
                                 ", 'y_low')) with vectors nohead lc rgb '#333333' lw 1.2 "
                                 "notitle"));
  }
  absl::StrAppend(&out, "plot ", absl::StrJoin(plots, ", \\\n     "), "\n\n");
  return out;
}

}  // namespace

absl::StatusOr<GnuplotFigure> BarChartFigure(const BarChart& chart) {
  DCS_RETURN_IF_ERROR(CheckChart(chart));
  std::vector<std::string> panels;
  for (size_t p = 0; p < chart.panels.size(); ++p) {
    panels.push_back(PanelScript(chart.panels[p], p));
  }
  return MultiplotFigure(
      chart.name, chart.title, Csv(chart), chart.columns, chart.panel_width, chart.panel_height,
      "# The value of column `c` on the row of series `s` in panel `p`, else NaN.\n"
      "sel(p, s, c) = (column('panel') == p && column('series') == s) ? column(c) : NaN\n"
      "set grid noxtics ytics\nset xtics scale 0\n\n",
      panels);
}

}  // namespace dcs::report
