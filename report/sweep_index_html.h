// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SWEEP_INDEX_HTML_H_
#define DCS_REPORT_SWEEP_INDEX_HTML_H_

// The `index.html` of a report directory (`dcs plot`): the report's table and every figure,
// each with links to its data (CSV) and gnuplot script, readable offline in a browser: one file
// with its style inline, no scripts, and nothing loaded but the figures beside it. Thread-safe
// (pure function).

#include <string>
#include <vector>

#include "absl/strings/string_view.h"
#include "report/gnuplot_figure.h"

namespace dcs::report {

// The page titled `title` (escaped), showing `report_table_html` as given (trusted HTML, e.g.
// a <table>; empty: no table section) and then each figure's image `<name>.<format>` by
// relative link: an <img> for SVG and PNG, an <object> (with a link as fallback) for PDF.
std::string SweepIndexHtml(absl::string_view title, absl::string_view report_table_html,
                           const std::vector<GnuplotFigure>& figures, FigureFormat format);

}  // namespace dcs::report

#endif  // DCS_REPORT_SWEEP_INDEX_HTML_H_
