// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_GNUPLOT_FIGURE_H_
#define DCS_COORDINATOR_GNUPLOT_FIGURE_H_

// A figure as gnuplot draws it: its data (CSV files with a header row) and a gnuplot script that
// reads them by relative name and writes `<name>.<format>`, so that a researcher can restyle a
// figure by editing its script beside its data. Nothing here runs gnuplot
// (services/cli/figure_render.h does); the chart builders (line_chart.h, bar_chart.h,
// heatmap_chart.h) make figures with the helpers below. Thread-safe (pure functions).
//
// Every script picks its terminal from the gnuplot variable `format` (svg unless set):
//   gnuplot NAME.gp                      -> NAME.svg
//   gnuplot -e "format='png'" NAME.gp    -> NAME.png (pngcairo)
//   gnuplot -e "format='pdf'" NAME.gp    -> NAME.pdf (pdfcairo)
// Text is drawn `noenhanced` (no sub/superscripts: _ ^ @ & are plain characters).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/enum_names.h"

namespace dcs::report {

enum class FigureFormat { kSvg, kPng, kPdf };

// As `--format` and file extensions spell them.
inline constexpr EnumName<FigureFormat> kFigureFormatNames[] = {
    {FigureFormat::kSvg, "svg"}, {FigureFormat::kPng, "png"}, {FigureFormat::kPdf, "pdf"}};
static_assert(InEnumOrder(kFigureFormatNames));

struct DataFile {
  std::string name;  // relative to the figure's directory, e.g. "learning_curves.csv"
  std::string csv;   // a header row, then the rows
};

struct GnuplotFigure {
  std::string name;   // the file stem of the script and of the image
  std::string title;  // for pages that show the figure (alt text, captions)
  std::vector<DataFile> data;
  std::string script;  // the whole `<name>.gp`

  std::string ScriptFileName() const { return name + ".gp"; }
  std::string ImageFileName(FigureFormat format) const;
};

// INVALID_ARGUMENT unless `name` is usable as a file stem in any directory: 1 to 100 of
// [A-Za-z0-9_.-], not starting with '.' or '-'.
absl::Status CheckFigureName(absl::string_view name);

// CheckFigureName, then INVALID_ARGUMENT naming the chart (`kind` '<name>') unless it has a
// panel, at least one column of them, and panels of at least 160 x 120 pixels.
absl::Status CheckPanelGrid(absl::string_view kind, absl::string_view name, size_t panels,
                            int columns, int panel_width, int panel_height);

// Okabe-Ito, the colour-blind-safe palette ("#rrggbb"): series i of a chart has colour
// SeriesColor(i), cycling after eight (blue, vermillion, green, orange, purple, sky blue,
// black, yellow). REQUIRES: index >= 0.
std::string SeriesColor(int index);
inline constexpr char kBaselineColor[] = "#000000";  // a baseline (static) drawn apart

// Where a panel's legend goes: inside the plot at a corner, in a column right of it, in rows
// above it, or none.
enum class LegendPlace {
  kTopRight,
  kTopLeft,
  kBottomRight,
  kBottomLeft,
  kOutsideRight,
  kAbove,
  kNone
};

// The `set key` command placing a legend (`unset key` for kNone), with the DCS look.
std::string KeyCommand(LegendPlace place);

// `text` as a gnuplot string literal: single-quoted (gnuplot does not interpret backslashes in
// them), a quote doubled, control characters (newlines, tabs) as spaces.
std::string GnuplotString(absl::string_view text);

// `text` as one CSV field (RFC 4180): quoted when it holds a comma, quote or line break.
// gnuplot splits quoted fields at commas, so figures put text columns after the numbers their
// scripts read.
std::string CsvField(absl::string_view text);

// A number as a CSV field: eight significant digits (every step count below 10^8 exactly).
// REQUIRES: `value` is finite.
std::string CsvNumber(double value);

// The opening of a figure's script: comments naming the figure, its data files and how to
// render it; the terminal chosen by `format` (unknown formats exit with status 3); the output
// `<name>.<format>`; the variable `fontsize`, the terminal's font size in points (a title:
// `font sprintf(',%d', fontsize + 2)`); CSV input whose first row names the columns
// (`using 'step':'iqm'`); a white background, `noenhanced` text, light grid, axes left and
// below. `width` x `height` in pixels (PDF: 100 pixels an inch).
std::string ScriptPreamble(const GnuplotFigure& figure, int width, int height);

// Panels laid out in rows of at most `columns` (gnuplot's multiplot), under a title band if the
// figure has a title; sizes in pixels.
struct PanelGrid {
  int rows = 1;
  int columns = 1;
  int width = 0;
  int height = 0;
};
PanelGrid LayOutPanels(int panels, int columns, int panel_width, int panel_height,
                       bool has_title);

// `set multiplot layout ROWS,COLUMNS [title ...]`, ending in a blank line.
std::string MultiplotCommand(const PanelGrid& grid, absl::string_view title);

// A figure of panels in a multiplot grid (LayOutPanels) whose data is one CSV file,
// `<name>.csv`: the script is the preamble, `data = '<name>.csv'`, `setup` (what every panel
// shares: functions, settings), the multiplot command, then each panel's script in order.
GnuplotFigure MultiplotFigure(absl::string_view name, absl::string_view title, std::string csv,
                              int columns, int panel_width, int panel_height,
                              absl::string_view setup,
                              const std::vector<std::string>& panel_scripts);

}  // namespace dcs::report

#endif  // DCS_COORDINATOR_GNUPLOT_FIGURE_H_
