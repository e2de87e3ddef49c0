// Copyright 2026 The DCS Authors.
#include "report/report_format.h"

#include <cctype>
#include <optional>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "common/round_trip.h"
#include "common/text_table.h"
#include "dcs/proto_json.h"

namespace dcs::report {
namespace {

using Rows = std::vector<std::vector<std::string>>;

// What marks an absent value in the plain formats (an empty cell, no improvement).
constexpr absl::string_view kNone = "-";

bool HasBaseline(const v1::SweepReport& report) { return !report.settings().baseline().empty(); }

// `value` with `digits` decimals; never "-0.0", which shows a sign that is not there.
std::string Fixed(double value, int digits) {
  std::string text = absl::StrFormat("%.*f", digits, value);
  if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

std::string Percent(double fraction) { return absl::StrFormat("%g%%", 100 * fraction); }

// A cell's values as plain text; `kNone` where absent.
struct CellText {
  std::string runs;         // "7/10"
  std::string iqm;          // "468.2 [454.7, 484.3]"
  std::string interval;     // "[450.1, 480.2]"
  std::string improvement;  // "0.83 [0.61, 0.98]"
  std::string holm;         // "0.0042 better", "0.31"
};

CellText TextOf(const v1::ReportCell& cell) {
  CellText text{.runs = cell.seeds() == 0 ? std::string(kNone)
                                          : absl::StrCat(cell.runs(), "/", cell.seeds()),
                .iqm = std::string(kNone),
                .interval = std::string(kNone),
                .improvement = std::string(kNone),
                .holm = std::string(kNone)};
  if (!cell.empty()) {
    const v1::ScoreSummary& summary = cell.summary();
    text.iqm = absl::StrCat(Fixed(summary.iqm(), 1), " [", Fixed(summary.q1(), 1), ", ",
                            Fixed(summary.q3(), 1), "]");
    text.interval =
        absl::StrCat("[", Fixed(summary.ci_low(), 1), ", ", Fixed(summary.ci_high(), 1), "]");
  }
  if (cell.has_improvement()) {
    const v1::Improvement& improvement = cell.improvement();
    text.improvement = absl::StrCat(Fixed(improvement.probability(), 2), " [",
                                    Fixed(improvement.ci_low(), 2), ", ",
                                    Fixed(improvement.ci_high(), 2), "]");
    text.holm = absl::StrFormat("%.2g", improvement.holm_p_value());
    if (improvement.significant()) {
      absl::StrAppend(&text.holm, improvement.probability() > 0.5 ? " better" : " worse");
    }
  }
  return text;
}

// The names of a mode's columns in the table, md and html formats.
std::vector<std::string> ModeColumns(const v1::SweepReport& report) {
  std::vector<std::string> columns = {"runs", "IQM [Q1, Q3]",
                                      Percent(report.settings().confidence()) + " CI"};
  if (HasBaseline(report)) {
    columns.push_back("P(>baseline)");
    columns.push_back("Holm p");
  }
  return columns;
}

// A mode's cells in the order of ModeColumns, the best IQM between `best_open` and
// `best_close`. Numbers only: nothing in them needs escaping in any format.
std::vector<std::string> ModeCells(const v1::SweepReport& report, const v1::ReportCell& cell,
                                   absl::string_view best_open, absl::string_view best_close) {
  CellText text = TextOf(cell);
  if (cell.best()) text.iqm = absl::StrCat(best_open, text.iqm, best_close);
  std::vector<std::string> cells = {text.runs, text.iqm, text.interval};
  if (HasBaseline(report)) {
    cells.push_back(text.improvement);
    cells.push_back(text.holm);
  }
  return cells;
}

std::string Title(const v1::SweepReport& report) {
  if (report.name().empty()) return absl::StrCat("Sweep ", report.sweep_id());
  if (report.sweep_id().empty()) return absl::StrCat("Sweep ", report.name());
  return absl::StrCat("Sweep ", report.name(), " (", report.sweep_id(), ")");
}

// What a cell is: the score read and the seeds asked.
std::string Header(const v1::SweepReport& report) {
  return absl::StrCat(Title(report), ": IQM [Q1, Q3] across seeds of ",
                      report.settings().score_rule(), "; ", report.seeds(),
                      " seeds asked per condition and mode.");
}

// How the statistics were computed, one sentence per line, `best_mark` naming how the format
// marks the best IQM.
std::vector<std::string> Footer(const v1::SweepReport& report, absl::string_view best_mark) {
  const v1::ReportSettings& settings = report.settings();
  std::vector<std::string> lines = {
      absl::StrCat(best_mark, ": the best IQM of its mode. ", settings.iqm_rule(), "; ",
                   settings.quartile_rule(), "."),
      absl::StrCat(Percent(settings.confidence()), " CI: ", settings.interval_rule(), "; ",
                   settings.bootstrap_resamples(), " resamples, seed ",
                   settings.bootstrap_seed(), ".")};
  if (HasBaseline(report)) {
    lines.push_back(absl::StrCat("P(>baseline): the probability of improvement over ",
                                 settings.baseline(), ": ", settings.improvement_rule(),
                                 "; its interval with the same bootstrap settings."));
    lines.push_back(absl::StrCat("Holm p: ", settings.significance_rule(), " (",
                                 1 - settings.confidence(),
                                 "): better or worse than the baseline as P(>baseline) is above "
                                 "or below 0.5."));
  }
  return lines;
}

// --- coverage (table, md and html) ---------------------------------------------------------

// "50k", "151.552k", "0".
std::string Steps(int64_t steps) {
  return steps == 0 ? "0" : absl::StrFormat("%gk", static_cast<double>(steps) / 1000);
}

std::string CoverageTitle(const v1::CoverageSection& section) {
  return absl::StrCat("Coverage of ", section.projection(), " (", section.cells(),
                      " cells): percent of the cells the runs visited over the run (mean and ",
                      "standard error across runs), and within each window of steps (mean).");
}

// The header row, then one row per condition and mode.
Rows CoverageRows(const v1::CoverageSection& section) {
  Rows rows = {{"condition", "mode", "runs", "run %"}};
  for (int w = 0; w < section.window_ends_size(); ++w) {
    rows[0].push_back(absl::StrCat(Steps(section.window_starts(w)), "-",
                                   Steps(section.window_ends(w)), " %"));
  }
  for (const v1::CoverageRow& row : section.rows()) {
    std::vector<std::string> line = {row.condition(), row.mode(), absl::StrCat(row.runs_size()),
                                     absl::StrCat(Fixed(row.mean(), 2), " +- ",
                                                  Fixed(row.sem(), 2))};
    for (double mean : row.window_means()) line.push_back(Fixed(mean, 2));
    rows.push_back(std::move(line));
  }
  return rows;
}

// One sentence per mode: its tests, or why there are none.
std::vector<std::string> CoverageTests(const v1::CoverageSection& section) {
  std::vector<std::string> lines;
  for (const v1::CoverageTest& test : section.tests()) {
    std::vector<std::string> parts;
    if (test.has_anova()) {
      const v1::CoverageAnova& anova = test.anova();
      parts.push_back(absl::StrFormat("one-way ANOVA across conditions F(%d, %d) = %.3g, p = %.3g",
                                      anova.df_between(), anova.df_within(), anova.f(),
                                      anova.p_value()));
    }
    if (test.has_correlation()) {
      const v1::CoverageCorrelation& r = test.correlation();
      parts.push_back(absl::StrFormat("Pearson r(score, coverage) = %.3f, p = %.3g (%d runs)",
                                      r.r(), r.p_value(), r.runs()));
    }
    if (!test.note().empty()) parts.push_back(test.note());
    lines.push_back(absl::StrCat(test.mode(), ": ", absl::StrJoin(parts, "; "), "."));
  }
  return lines;
}

// --- table ---------------------------------------------------------------------------------

std::string FormatTable(const v1::SweepReport& report) {
  Rows rows = {{"CONDITION", "FAMILY"}};
  std::vector<bool> right = {false, false};
  for (const std::string& mode : report.modes()) {
    for (const std::string& column : ModeColumns(report)) {
      rows[0].push_back(absl::StrCat(mode, ":", column));
      right.push_back(true);
    }
  }
  for (const v1::ReportRow& row : report.rows()) {
    std::vector<std::string> line = {row.condition(), row.family()};
    for (const v1::ReportCell& cell : row.cells()) {
      for (std::string& text : ModeCells(report, cell, "*", "")) line.push_back(std::move(text));
    }
    rows.push_back(std::move(line));
  }
  std::string out = absl::StrCat(Header(report), "\n\n", RenderTable(rows, right), "\n",
                                 absl::StrJoin(Footer(report, "*"), "\n"), "\n");
  for (const v1::CoverageSection& section : report.coverage()) {
    const Rows coverage = CoverageRows(section);
    std::vector<bool> numbers(coverage[0].size(), true);
    numbers[0] = numbers[1] = false;
    absl::StrAppend(&out, "\n", CoverageTitle(section), "\n\n", RenderTable(coverage, numbers),
                    "\n", absl::StrJoin(CoverageTests(section), "\n"), "\n");
  }
  return out;
}

// --- md ------------------------------------------------------------------------------------

std::string MarkdownEscape(absl::string_view text) {
  std::string out;
  for (char c : text) {
    if (absl::string_view("\\`*_|<").find(c) != absl::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

std::string FormatMarkdown(const v1::SweepReport& report) {
  std::vector<std::string> header = {"condition", "family"};
  std::vector<std::string> rule = {"---", "---"};
  for (const std::string& mode : report.modes()) {
    for (const std::string& column : ModeColumns(report)) {
      header.push_back(MarkdownEscape(absl::StrCat(mode, " ", column)));
      rule.push_back("--:");
    }
  }
  std::string out = absl::StrCat(MarkdownEscape(Header(report)), "\n\n| ",
                                 absl::StrJoin(header, " | "), " |\n|",
                                 absl::StrJoin(rule, "|"), "|\n");
  for (const v1::ReportRow& row : report.rows()) {
    std::vector<std::string> line = {MarkdownEscape(row.condition()),
                                     MarkdownEscape(row.family())};
    for (const v1::ReportCell& cell : row.cells()) {
      for (std::string& text : ModeCells(report, cell, "**", "**")) {
        line.push_back(std::move(text));
      }
    }
    absl::StrAppend(&out, "| ", absl::StrJoin(line, " | "), " |\n");
  }
  absl::StrAppend(&out, "\n");
  for (const std::string& sentence : Footer(report, "Bold")) {
    absl::StrAppend(&out, MarkdownEscape(sentence), "\n");
  }
  for (const v1::CoverageSection& section : report.coverage()) {
    const Rows coverage = CoverageRows(section);
    absl::StrAppend(&out, "\n", MarkdownEscape(CoverageTitle(section)), "\n\n");
    for (size_t r = 0; r < coverage.size(); ++r) {
      std::vector<std::string> line;
      for (const std::string& text : coverage[r]) line.push_back(MarkdownEscape(text));
      absl::StrAppend(&out, "| ", absl::StrJoin(line, " | "), " |\n");
      if (r == 0) {
        std::vector<std::string> alignment(line.size(), "--:");
        alignment[0] = alignment[1] = "---";
        absl::StrAppend(&out, "|", absl::StrJoin(alignment, "|"), "|\n");
      }
    }
    absl::StrAppend(&out, "\n");
    for (const std::string& sentence : CoverageTests(section)) {
      absl::StrAppend(&out, MarkdownEscape(sentence), "\n");
    }
  }
  return out;
}

// --- csv -----------------------------------------------------------------------------------

// RFC 4180: quoted when it holds a comma, a quote or a line break; quotes doubled.
std::string CsvField(absl::string_view text) {
  if (text.find_first_of(",\"\r\n") == absl::string_view::npos) return std::string(text);
  return absl::StrCat("\"", absl::StrReplaceAll(text, {{"\"", "\"\""}}), "\"");
}

std::string FormatCsv(const v1::SweepReport& report) {
  std::string out =
      "checkpoint,split,condition,family,baseline,mode,runs,seeds,iqm,q1,q3,ci_low,ci_high,"
      "p_improvement,p_improvement_ci_low,p_improvement_ci_high,p_value,holm_p_value,"
      "significant,best\n";
  const auto number = [](bool present, double value) {
    return present ? RoundTrip(value) : std::string();
  };
  for (const v1::ReportRow& row : report.rows()) {
    for (const v1::ReportCell& cell : row.cells()) {
      const bool full = !cell.empty();
      const bool improved = cell.has_improvement();
      const v1::ScoreSummary& summary = cell.summary();
      const v1::Improvement& improvement = cell.improvement();
      const std::vector<std::string> fields = {
          CsvField(report.settings().checkpoint()), CsvField(report.settings().split()),
          CsvField(row.condition()), CsvField(row.family()), row.baseline() ? "true" : "false",
          CsvField(cell.mode()), absl::StrCat(cell.runs()), absl::StrCat(cell.seeds()),
          number(full, summary.iqm()), number(full, summary.q1()), number(full, summary.q3()),
          number(full, summary.ci_low()), number(full, summary.ci_high()),
          number(improved, improvement.probability()), number(improved, improvement.ci_low()),
          number(improved, improvement.ci_high()), number(improved, improvement.p_value()),
          number(improved, improvement.holm_p_value()),
          improved ? (improvement.significant() ? "true" : "false") : "",
          cell.best() ? "true" : "false"};
      absl::StrAppend(&out, absl::StrJoin(fields, ","), "\n");
    }
  }
  return out;
}

// --- latex ---------------------------------------------------------------------------------

std::string LatexEscape(absl::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '<': out += "\\textless{}"; break;
      case '>': out += "\\textgreater{}"; break;
      // Braced, so that a cell starting with "[" is not read as the optional argument of the
      // "\\" ending the row before.
      case '[': out += "{[}"; break;
      case ']': out += "{]}"; break;
      case '&': case '%': case '$': case '#': case '_': case '{': case '}':
        out += '\\';
        out += c;
        break;
      default: out += c;
    }
  }
  return out;
}

// A cell of numbers (digits, signs, brackets) with typeset minus signs; "--" when absent.
std::string LatexNumbers(const std::string& text) {
  if (text == kNone) return "--";
  return absl::StrReplaceAll(text, {{"-", "$-$"}});
}

// A label from the sweep's name or id: lower-case letters, digits and hyphens.
std::string LatexLabel(const v1::SweepReport& report) {
  std::string label;
  for (char c : report.name().empty() ? report.sweep_id() : report.name()) {
    const auto u = static_cast<unsigned char>(c);
    label += std::isalnum(u) ? static_cast<char>(std::tolower(u)) : '-';
  }
  return absl::StrCat("tab:sweep-", label.empty() ? "report" : label);
}

std::string LatexCaption(const v1::SweepReport& report) {
  const v1::ReportSettings& settings = report.settings();
  std::string caption = absl::StrCat(
      LatexEscape(Title(report)), ", checkpoint ", LatexEscape(settings.checkpoint()),
      ", split ", LatexEscape(settings.split()), ": IQM [Q1, Q3] across seeds of ",
      LatexEscape(settings.score_rule()), "; ", report.seeds(),
      " seeds per condition and mode ($^\\dagger$: fewer finished runs). Bold: the best IQM of "
      "its mode. ",
      LatexEscape(absl::StrCat(settings.iqm_rule(), "; ", settings.quartile_rule(), ".")),
      " Bootstrap: ", LatexEscape(Percent(settings.confidence())), " percentile intervals, ",
      settings.bootstrap_resamples(), " resamples, seed ", settings.bootstrap_seed(), ".");
  if (HasBaseline(report)) {
    absl::StrAppend(&caption, " P($>$baseline): the probability of improvement over ",
                    LatexEscape(settings.baseline()), ", ",
                    LatexEscape(settings.improvement_rule()), "; $^{*}$: ",
                    LatexEscape(settings.significance_rule()), " (",
                    1 - settings.confidence(), ").");
  }
  return caption;
}

std::string FormatLatex(const v1::SweepReport& report) {
  const bool improvement = HasBaseline(report);
  const int per_mode = improvement ? 2 : 1;
  // A comment ends at the line's end: the title on one line.
  const std::string title = absl::StrReplaceAll(Title(report), {{"\n", " "}, {"\r", " "}});
  std::string out = absl::StrCat("% ", title, ". Requires \\usepackage{booktabs}.\n",
                                 "\\begin{table}[htbp]\n\\centering\n\\caption{",
                                 LatexCaption(report), "}\n\\label{", LatexLabel(report),
                                 "}\n\\begin{tabular}{ll",
                                 std::string(per_mode * report.modes_size(), 'c'),
                                 "}\n\\toprule\n");
  if (improvement) {
    std::string modes = " &";
    std::string rules;
    for (int m = 0; m < report.modes_size(); ++m) {
      const int first = 3 + 2 * m;
      absl::StrAppend(&modes, " & \\multicolumn{2}{c}{", LatexEscape(report.modes(m)), "}");
      absl::StrAppend(&rules, "\\cmidrule(lr){", first, "-", first + 1, "}");
    }
    absl::StrAppend(&out, modes, " \\\\\n", rules, "\nCondition & Family");
    for (int m = 0; m < report.modes_size(); ++m) {
      absl::StrAppend(&out, " & IQM [Q1, Q3] & P($>$baseline)");
    }
  } else {
    absl::StrAppend(&out, "Condition & Family");
    for (const std::string& mode : report.modes()) absl::StrAppend(&out, " & ", LatexEscape(mode));
  }
  absl::StrAppend(&out, " \\\\\n\\midrule\n");
  for (const v1::ReportRow& row : report.rows()) {
    absl::StrAppend(&out, LatexEscape(row.condition()), " & ", LatexEscape(row.family()));
    for (const v1::ReportCell& cell : row.cells()) {
      const CellText text = TextOf(cell);
      std::string iqm = LatexNumbers(text.iqm);
      if (cell.best()) iqm = absl::StrCat("\\textbf{", iqm, "}");
      if (!cell.empty() && cell.runs() < cell.seeds()) absl::StrAppend(&iqm, "$^\\dagger$");
      absl::StrAppend(&out, " & ", iqm);
      if (improvement) {
        absl::StrAppend(&out, " & ", LatexNumbers(text.improvement),
                        cell.improvement().significant() ? "$^{*}$" : "");
      }
    }
    absl::StrAppend(&out, " \\\\\n");
  }
  absl::StrAppend(&out, "\\bottomrule\n\\end{tabular}\n\\end{table}\n");
  return out;
}

// --- html ----------------------------------------------------------------------------------

std::string HtmlEscape(absl::string_view text) {
  return absl::StrReplaceAll(text, {{"&", "&amp;"},
                                    {"<", "&lt;"},
                                    {">", "&gt;"},
                                    {"\"", "&quot;"},
                                    {"'", "&#39;"}});
}

std::string FormatHtml(const v1::SweepReport& report) {
  const std::vector<std::string> columns = ModeColumns(report);
  std::string out = absl::StrCat("<table class=\"dcs-sweep-report\">\n<caption>",
                                 HtmlEscape(Header(report)), "</caption>\n<thead>\n<tr>",
                                 "<th rowspan=\"2\">condition</th><th rowspan=\"2\">family</th>");
  for (const std::string& mode : report.modes()) {
    absl::StrAppend(&out, "<th colspan=\"", columns.size(), "\">", HtmlEscape(mode), "</th>");
  }
  absl::StrAppend(&out, "</tr>\n<tr>");
  for (int m = 0; m < report.modes_size(); ++m) {
    for (const std::string& column : columns) {
      absl::StrAppend(&out, "<th>", HtmlEscape(column), "</th>");
    }
  }
  absl::StrAppend(&out, "</tr>\n</thead>\n<tbody>\n");
  for (const v1::ReportRow& row : report.rows()) {
    absl::StrAppend(&out, "<tr><td>", HtmlEscape(row.condition()), "</td><td>",
                    HtmlEscape(row.family()), "</td>");
    for (const v1::ReportCell& cell : row.cells()) {
      for (const std::string& text : ModeCells(report, cell, "<strong>", "</strong>")) {
        absl::StrAppend(&out, "<td>", text, "</td>");
      }
    }
    absl::StrAppend(&out, "</tr>\n");
  }
  absl::StrAppend(&out, "</tbody>\n<tfoot>\n<tr><td colspan=\"",
                  2 + columns.size() * report.modes_size(), "\">",
                  HtmlEscape(absl::StrJoin(Footer(report, "Bold"), " ")),
                  "</td></tr>\n</tfoot>\n</table>\n");
  for (const v1::CoverageSection& section : report.coverage()) {
    const Rows coverage = CoverageRows(section);
    absl::StrAppend(&out, "<table class=\"dcs-coverage\">\n<caption>",
                    HtmlEscape(CoverageTitle(section)), "</caption>\n");
    for (size_t r = 0; r < coverage.size(); ++r) {
      const absl::string_view tag = r == 0 ? "th" : "td";
      absl::StrAppend(&out, "<tr>");
      for (const std::string& text : coverage[r]) {
        absl::StrAppend(&out, "<", tag, ">", HtmlEscape(text), "</", tag, ">");
      }
      absl::StrAppend(&out, "</tr>\n");
    }
    absl::StrAppend(&out, "<tfoot>\n<tr><td colspan=\"", coverage[0].size(), "\">",
                    HtmlEscape(absl::StrJoin(CoverageTests(section), " ")),
                    "</td></tr>\n</tfoot>\n</table>\n");
  }
  return out;
}

}  // namespace

std::string FormatReport(const v1::SweepReport& report, ReportFormat format) {
  switch (format) {
    case ReportFormat::kTable:
      return FormatTable(report);
    case ReportFormat::kMarkdown:
      return FormatMarkdown(report);
    case ReportFormat::kCsv:
      return FormatCsv(report);
    case ReportFormat::kJson:
      return ProtoToJson(report) + "\n";
    case ReportFormat::kLatex:
      return FormatLatex(report);
    case ReportFormat::kHtml:
      return FormatHtml(report);
  }
  return {};  // unreachable: every format has its case
}

}  // namespace dcs::report
