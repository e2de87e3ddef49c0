// Copyright 2026 The DCS Authors.
#include "report/sweep_index_html.h"

#include "absl/strings/str_cat.h"

namespace dcs::report {
namespace {

constexpr char kStyle[] = R"(
body { font-family: Helvetica, Arial, sans-serif; color: #222; margin: 24px auto;
       max-width: 1400px; padding: 0 16px; line-height: 1.4; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 17px; margin: 28px 0 8px; }
nav a { margin-right: 14px; }
table { border-collapse: collapse; font-size: 13px; margin: 8px 0; }
caption { text-align: left; font-weight: bold; padding-bottom: 6px; }
th, td { border-bottom: 1px solid #ddd; padding: 3px 10px; text-align: right; }
th:first-child, td:first-child { text-align: left; }
thead th { border-bottom: 2px solid #888; }
tfoot td { color: #555; font-size: 12px; border-bottom: none; text-align: left; }
figure { margin: 0 0 24px; }
figure img, figure object { max-width: 100%; height: auto; border: 1px solid #eee; }
figure object { width: 100%; height: 640px; }
figcaption { font-size: 13px; color: #444; margin-top: 4px; }
code { background: #f4f4f4; padding: 0 3px; }
)";

std::string HtmlEscape(absl::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string FigureHtml(const GnuplotFigure& figure, FigureFormat format) {
  const std::string image = HtmlEscape(figure.ImageFileName(format));
  const std::string title = HtmlEscape(figure.title.empty() ? figure.name : figure.title);
  std::string out = absl::StrCat("<figure id=\"", HtmlEscape(figure.name), "\">\n");
  if (format == FigureFormat::kPdf) {
    absl::StrAppend(&out, "<object data=\"", image, "\" type=\"application/pdf\" title=\"",
                    title, "\"><a href=\"", image, "\">", image, "</a></object>\n");
  } else {
    absl::StrAppend(&out, "<a href=\"", image, "\"><img src=\"", image, "\" alt=\"", title,
                    "\"></a>\n");
  }
  absl::StrAppend(&out, "<figcaption>", title, ". Image: <a href=\"", image, "\">", image,
                  "</a>; data:");
  for (const DataFile& data : figure.data) {
    absl::StrAppend(&out, " <a href=\"", HtmlEscape(data.name), "\">", HtmlEscape(data.name),
                    "</a>");
  }
  const std::string script = HtmlEscape(figure.ScriptFileName());
  absl::StrAppend(&out, "; script: <a href=\"", script, "\">", script,
                  "</a> (restyle it and run <code>gnuplot ", script,
                  "</code> here).</figcaption>\n</figure>\n");
  return out;
}

}  // namespace

std::string SweepIndexHtml(absl::string_view title, absl::string_view report_table_html,
                           const std::vector<GnuplotFigure>& figures, FigureFormat format) {
  const std::string escaped_title = HtmlEscape(title);
  std::string out = absl::StrCat(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n",
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>",
      escaped_title, "</title>\n<style>", kStyle, "</style>\n</head>\n<body>\n<h1>",
      escaped_title, "</h1>\n<nav>");
  if (!report_table_html.empty()) absl::StrAppend(&out, "<a href=\"#report\">Report</a>");
  for (const GnuplotFigure& figure : figures) {
    absl::StrAppend(&out, "<a href=\"#", HtmlEscape(figure.name), "\">",
                    HtmlEscape(figure.name), "</a>");
  }
  absl::StrAppend(&out, "</nav>\n");
  if (!report_table_html.empty()) {
    absl::StrAppend(&out, "<section id=\"report\">\n<h2>Report</h2>\n", report_table_html,
                    "\n</section>\n");
  }
  if (!figures.empty()) absl::StrAppend(&out, "<section id=\"figures\">\n<h2>Figures</h2>\n");
  for (const GnuplotFigure& figure : figures) absl::StrAppend(&out, FigureHtml(figure, format));
  if (!figures.empty()) absl::StrAppend(&out, "</section>\n");
  absl::StrAppend(&out, "</body>\n</html>\n");
  return out;
}

}  // namespace dcs::report
