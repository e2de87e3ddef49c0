// Copyright 2026 The DCS Authors.
#include "report/gnuplot_figure.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::report {
namespace {

constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#E69F00",
                                    "#CC79A7", "#56B4E9", "#000000", "#F0E442"};

}  // namespace

std::string GnuplotFigure::ImageFileName(FigureFormat format) const {
  return absl::StrCat(name, ".", NameOf(kFigureFormatNames, format));
}

absl::Status CheckFigureName(absl::string_view name) {
  bool ok = !name.empty() && name.size() <= 100 && name.front() != '.' && name.front() != '-';
  for (const char c : name) {
    ok = ok && (absl::ascii_isalnum(c) || c == '_' || c == '.' || c == '-');
  }
  if (ok) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(
      "figure name '", name, "' is not a file stem (1 to 100 of A-Z a-z 0-9 _ . -)"));
}

absl::Status CheckPanelGrid(absl::string_view kind, absl::string_view name, size_t panels,
                            int columns, int panel_width, int panel_height) {
  DCS_RETURN_IF_ERROR(CheckFigureName(name));
  if (panels == 0 || columns < 1 || panel_width < 160 || panel_height < 120) {
    return absl::InvalidArgumentError(
        absl::StrCat(kind, " '", name,
                     "' needs a panel, columns >= 1 and panels of at least 160 x 120 pixels"));
  }
  return absl::OkStatus();
}

std::string SeriesColor(int index) { return kPalette[index % std::size(kPalette)]; }

std::string GnuplotString(absl::string_view text) {
  std::string out = "'";
  for (const char c : text) {
    if (c == '\'') {
      out += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      out += ' ';
    } else {
      out += c;
    }
  }
  out += "'";
  return out;
}

std::string KeyCommand(LegendPlace place) {
  const char* where = "";
  switch (place) {
    case LegendPlace::kTopRight: where = "top right inside"; break;
    case LegendPlace::kTopLeft: where = "top left inside"; break;
    case LegendPlace::kBottomRight: where = "bottom right inside"; break;
    case LegendPlace::kBottomLeft: where = "bottom left inside"; break;
    case LegendPlace::kOutsideRight: where = "top right outside vertical"; break;
    case LegendPlace::kAbove: where = "above horizontal"; break;
    case LegendPlace::kNone: return "unset key\n";
  }
  return absl::StrCat("set key ", where,
                      " Left reverse opaque box lc rgb '#dddddd' samplen 2.5 spacing 1.1 "
                      "width 1\n");
}

std::string CsvField(absl::string_view text) {
  if (text.find_first_of(",\"\r\n") == absl::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += "\"";
  return out;
}

std::string CsvNumber(double value) {
  if (value == 0) return "0";  // not "-0"
  return absl::StrFormat("%.8g", value);
}

std::string ScriptPreamble(const GnuplotFigure& figure, int width, int height) {
  std::vector<std::string> data_names;
  for (const DataFile& data : figure.data) data_names.push_back(data.name);
  const std::string size = absl::StrCat(width, ",", height);
  const std::string pdf_size = absl::StrFormat("%.2fin,%.2fin", width / 100.0, height / 100.0);
  std::string out = absl::StrCat(
      "# ", figure.title, "\n",
      "# Data: ", absl::StrJoin(data_names, ", "), " (CSV; the first row names the columns).\n",
      "# Render: gnuplot ", figure.ScriptFileName(), " (SVG), or gnuplot -e \"format='png'\" ",
      figure.ScriptFileName(), " (also 'pdf'),\n# in this directory: writes ", figure.name,
      ".<format>.\n\n");
  absl::StrAppend(
      &out, "if (!exists('format')) format = 'svg'\n",
      "if (format eq 'svg') {\n",
      "  set terminal svg size ", size,
      " fixed noenhanced font 'Helvetica,12' background '#ffffff'\n",
      "  fontsize = 12\n}\n",
      "if (format eq 'png') {\n",
      "  set terminal pngcairo size ", size,
      " noenhanced font 'Sans,10' linewidth 1.25 background '#ffffff'\n",
      "  fontsize = 10\n}\n",
      "if (format eq 'pdf') {\n",
      "  set terminal pdfcairo size ", pdf_size,
      " noenhanced font 'Sans,9' linewidth 1.25 background '#ffffff'\n",
      "  fontsize = 9\n}\n",
      "if (format ne 'svg' && format ne 'png' && format ne 'pdf') {\n",
      "  print 'unknown format '.format.' (svg, png or pdf)'\n  exit status 3\n}\n",
      "set output ", GnuplotString(figure.name), ".'.'.format\n",
      "set datafile separator comma\n",
      "set datafile columnheaders\n",
      "set termoption noenhanced\n",
      "set border 3 lc rgb '#555555'\n",
      "set tics nomirror out scale 0.6 textcolor rgb '#333333'\n",
      "set grid back lc rgb '#e6e6e6' lw 1 dt 1\n",
      "set key noautotitle textcolor rgb '#222222'\n\n");
  return out;
}

PanelGrid LayOutPanels(int panels, int columns, int panel_width, int panel_height,
                       bool has_title) {
  PanelGrid grid;
  grid.columns = std::max(1, std::min(columns, panels));
  grid.rows = std::max(1, (panels + grid.columns - 1) / grid.columns);
  grid.width = grid.columns * panel_width;
  grid.height = grid.rows * panel_height + (has_title ? 36 : 0);
  return grid;
}

std::string MultiplotCommand(const PanelGrid& grid, absl::string_view title) {
  std::string out = absl::StrCat("set multiplot layout ", grid.rows, ",", grid.columns);
  if (!title.empty()) {
    absl::StrAppend(&out, " title ", GnuplotString(title), " font sprintf(',%d', fontsize + 3)");
  }
  absl::StrAppend(&out, "\n\n");
  return out;
}

GnuplotFigure MultiplotFigure(absl::string_view name, absl::string_view title, std::string csv,
                              int columns, int panel_width, int panel_height,
                              absl::string_view setup,
                              const std::vector<std::string>& panel_scripts) {
  const PanelGrid grid = LayOutPanels(static_cast<int>(panel_scripts.size()), columns,
                                      panel_width, panel_height, !title.empty());
  GnuplotFigure figure{.name = std::string(name), .title = std::string(title)};
  const std::string data_name = absl::StrCat(name, ".csv");
  figure.data.push_back({.name = data_name, .csv = std::move(csv)});
  figure.script = ScriptPreamble(figure, grid.width, grid.height);
  absl::StrAppend(&figure.script, "data = ", GnuplotString(data_name), "\n", setup,
                  MultiplotCommand(grid, title));
  for (const std::string& panel : panel_scripts) absl::StrAppend(&figure.script, panel);
  absl::StrAppend(&figure.script, "unset multiplot\n");
  return figure;
}

}  // namespace dcs::report
