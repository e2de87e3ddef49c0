// Copyright 2026 The DCS Authors.
#include "report/heatmap_chart.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::report {
namespace {

constexpr char kNegativeColor[] = "#D55E00";  // Okabe-Ito vermillion
constexpr char kZeroColor[] = "#f7f7f7";
constexpr char kPositiveColor[] = "#0072B2";  // Okabe-Ito blue
constexpr char kMissingColor[] = "#e0e0e0";
constexpr int kBlack = 0;
constexpr int kWhite = 0xffffff;

absl::Status CheckHeatmap(const Heatmap& heatmap) {
  DCS_RETURN_IF_ERROR(CheckFigureName(heatmap.name));
  if (heatmap.row_labels.empty() || heatmap.column_labels.empty() ||
      heatmap.values.size() != heatmap.row_labels.size() || heatmap.decimals < 0 ||
      heatmap.decimals > 6) {
    return absl::InvalidArgumentError(absl::StrCat(
        "heatmap '", heatmap.name, "' needs rows and columns, a row of values per row label (",
        heatmap.row_labels.size(), " labels, ", heatmap.values.size(),
        " rows) and 0 to 6 decimals"));
  }
  for (size_t r = 0; r < heatmap.values.size(); ++r) {
    const std::vector<double>& row = heatmap.values[r];
    if (row.size() != heatmap.column_labels.size()) {
      return absl::InvalidArgumentError(absl::StrCat("heatmap '", heatmap.name, "', row ", r,
                                                     ": ", row.size(), " values for ",
                                                     heatmap.column_labels.size(), " columns"));
    }
    if (std::any_of(row.begin(), row.end(), [](double v) { return std::isinf(v); })) {
      return absl::InvalidArgumentError(
          absl::StrCat("heatmap '", heatmap.name, "', row ", r, ": values must be finite"));
    }
  }
  return absl::OkStatus();
}

// The colour scale's half-width: the largest |value|, 1 without values (or all 0).
double ScaleLimit(const Heatmap& heatmap) {
  double limit = 0;
  for (const std::vector<double>& row : heatmap.values) {
    for (const double v : row) {
      if (!std::isnan(v)) limit = std::max(limit, std::abs(v));
    }
  }
  return limit > 0 ? limit : 1;
}

std::string Csv(const Heatmap& heatmap, double limit) {
  std::string csv = "row,column,value,text_color,text,row_label,column_label\n";
  for (size_t r = 0; r < heatmap.values.size(); ++r) {
    for (size_t c = 0; c < heatmap.column_labels.size(); ++c) {
      const double v = heatmap.values[r][c];
      const bool has_value = !std::isnan(v);
      // White numbers on the darker ends of the scale.
      const int text_color = has_value && std::abs(v) > 0.6 * limit ? kWhite : kBlack;
      // One format string per call: clang checks StrFormat's formats at compile time.
      const std::string text = !has_value          ? std::string("n/a")
                               : heatmap.diverging ? absl::StrFormat("%+.*f", heatmap.decimals, v)
                                                   : absl::StrFormat("%.*f", heatmap.decimals, v);
      absl::StrAppend(&csv, r, ",", c, ",", has_value ? CsvNumber(v) : "", ",", text_color, ",",
                      CsvField(text), ",", CsvField(heatmap.row_labels[r]), ",",
                      CsvField(heatmap.column_labels[c]), "\n");
    }
  }
  return csv;
}

std::string Tics(const std::vector<std::string>& labels) {
  std::vector<std::string> tics;
  for (size_t i = 0; i < labels.size(); ++i) {
    tics.push_back(absl::StrCat(GnuplotString(labels[i]), " ", i));
  }
  return absl::StrCat("(", absl::StrJoin(tics, ", "), ")");
}

}  // namespace

absl::StatusOr<GnuplotFigure> HeatmapFigure(const Heatmap& heatmap) {
  DCS_RETURN_IF_ERROR(CheckHeatmap(heatmap));
  const int rows = static_cast<int>(heatmap.row_labels.size());
  const int columns = static_cast<int>(heatmap.column_labels.size());
  const double limit = ScaleLimit(heatmap);
  GnuplotFigure figure{.name = heatmap.name, .title = heatmap.title};
  const std::string data_name = absl::StrCat(heatmap.name, ".csv");
  figure.data.push_back({.name = data_name, .csv = Csv(heatmap, limit)});
  size_t longest_row_label = 0;
  for (const std::string& label : heatmap.row_labels) {
    longest_row_label = std::max(longest_row_label, label.size());
  }
  const int width = 150 + 8 * static_cast<int>(longest_row_label) + 110 * columns + 160;
  const int height = std::max(340, 140 + 48 * rows);  // tall enough for the colour bar's label
  figure.script = ScriptPreamble(figure, width, height);
  absl::StrAppend(
      &figure.script, "data = ", GnuplotString(data_name), "\n",
      "set title ", GnuplotString(heatmap.title), " font sprintf(',%d', fontsize + 2)\n",
      "set xlabel ", GnuplotString(heatmap.x_label), "\n",
      "set ylabel ", GnuplotString(heatmap.y_label), "\n",
      "set cblabel ", GnuplotString(heatmap.value_label), "\n",
      "unset grid\nunset key\nset border 0\n",
      "set xtics ", Tics(heatmap.column_labels), " scale 0\n",
      "set ytics ", Tics(heatmap.row_labels), " scale 0\n",
      "set xrange [-0.5:", columns - 0.5, "]\n",
      "set yrange [", rows - 0.5, ":-0.5]  # the first row at the top\n",
      heatmap.diverging
          ? absl::StrCat("# Diverging around 0: vermillion below, blue above (Okabe-Ito).\n",
                         "set palette defined (-1 '", kNegativeColor, "', 0 '", kZeroColor,
                         "', 1 '", kPositiveColor, "')\n", "set cbrange [", CsvNumber(-limit),
                         ":", CsvNumber(limit), "]\n")
          : absl::StrCat("# From 0 up: white to blue (Okabe-Ito).\n", "set palette defined (0 '",
                         kZeroColor, "', 1 '", kPositiveColor, "')\n", "set cbrange [0:",
                         CsvNumber(limit), "]\n"),
      "set cbtics scale 0.5\n",
      "set style fill solid 1.0 border lc rgb '#ffffff'\n",
      "plot data using 'column':'row':(0.5):(0.5) with boxxyerror fc rgb '", kMissingColor,
      "', \\\n",
      "     data using 'column':'row':(0.5):(0.5):'value' with boxxyerror fc palette, \\\n",
      "     data using 'column':'row':(strcol('text')):'text_color' with labels ",
      "textcolor rgb variable\n");
  return figure;
}

}  // namespace dcs::report
