// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_REPORT_FORMAT_H_
#define DCS_REPORT_REPORT_FORMAT_H_

// A sweep's report (report/sweep_report.h) as text: an aligned table for a terminal,
// Markdown, CSV, JSON, LaTeX (booktabs) and HTML. The human formats (all but csv and json)
// state the score read in a header, mark the best IQM of each mode, and say how the statistics
// were computed (quartile rule, bootstrap resamples and seed) in a footer; LaTeX says both in
// its caption. Thread-safe (pure functions).

#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/enum_names.h"
#include "dcs/v1/report.pb.h"

namespace dcs::report {

enum class ReportFormat { kTable, kMarkdown, kCsv, kJson, kLatex, kHtml };

// The choices of `--format`, as they are spelled there.
inline constexpr EnumName<ReportFormat> kReportFormatNames[] = {
    {ReportFormat::kTable, "table"}, {ReportFormat::kMarkdown, "md"},
    {ReportFormat::kCsv, "csv"},     {ReportFormat::kJson, "json"},
    {ReportFormat::kLatex, "latex"}, {ReportFormat::kHtml, "html"}};
static_assert(InEnumOrder(kReportFormatNames));

// `report` as `format`, ending with a newline:
// - table: aligned plain text; "*" before the best IQM of each mode.
// - md: a GitHub table between a header and a footer paragraph; the best IQM in bold.
// - csv: a header, then one row per condition and mode (rows in the report's order, modes in
//   its order), numbers as their shortest round-trip text, empty fields for absent values.
// - json: the SweepReport in protobuf's JSON mapping (dcs/proto_json.h); parses back equal.
// - latex: a booktabs table (\toprule, \midrule, \bottomrule; needs \usepackage{booktabs})
//   with IQM [Q1, Q3] cells, the best in \textbf, "$^\dagger$" on cells with fewer runs than
//   seeds, and a caption stating the checkpoint, split, seeds and bootstrap settings.
// - html: a <table> with a <caption> and a <tfoot>; the best IQM in <strong>.
// With coverage sections (report/coverage_report.h), table, md and html follow the scores
// with one more table per projection (per condition and mode: runs, run coverage mean +- SEM,
// each window's mean) and a sentence per mode with its ANOVA and correlation; json holds them
// too; csv and latex are the score table only.
// Text from the report (condition names, ...) is escaped for each format.
std::string FormatReport(const v1::SweepReport& report, ReportFormat format);

}  // namespace dcs::report

#endif  // DCS_REPORT_REPORT_FORMAT_H_
