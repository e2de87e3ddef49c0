// Copyright 2026 The DCS Authors.
#include "services/cli/report_commands.h"

#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "report/report_format.h"
#include "report/study_figures.h"
#include "report/study_report.h"
#include "report/sweep_figures.h"
#include "report/sweep_index_html.h"
#include "report/sweep_report.h"
#include "services/cli/cluster_client.h"
#include "services/cli/command_output.h"
#include "services/cli/figure_render.h"
#include "services/cli/run_client.h"
#include "services/cli/study_client.h"
#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

struct ReportFlags {
  std::string sweep_id;
  report::ReportOptions options;
  report::ReportFormat format = report::ReportFormat::kTable;  // --format, else -o's
  const CLI::Option* format_option = nullptr;
  int top = 20;  // a study sweep's: the best trials shown and counted
};

struct PlotFlags {
  std::string sweep_id;
  std::string out;
  report::FigureFormat format = report::FigureFormat::kSvg;
  int top = 20;  // as ReportFlags'
};

// A study sweep's report (report/study_report.h), with its study's trials.
absl::StatusOr<v1::StudyReport> FetchStudyReport(const GlobalFlags& flags,
                                                 const v1::SweepResults& results, int top,
                                                 const report::ReportOptions& options,
                                                 std::vector<coordinator::StudyTrial>* trials) {
  DCS_ASSIGN_OR_RETURN(
      *trials, ConnectStudies(CoordinatorAddress(flags), flags.timeout)->Trials(results.study_id()));
  return report::BuildStudyReport(results, *trials, top, options);
}

int ReportCommand(const GlobalFlags& flags, ReportFlags report_flags) {
  const report::ReportFormat from_output = flags.output == OutputFormat::kJson
                                               ? report::ReportFormat::kJson
                                           : flags.output == OutputFormat::kCsv
                                               ? report::ReportFormat::kCsv
                                               : report::ReportFormat::kTable;
  if (report_flags.format_option->count() == 0) {
    report_flags.format = from_output;
  } else if (flags.output != OutputFormat::kTable && report_flags.format != from_output) {
    return FailCommand(UsageError(absl::StrCat(
        "-o ", NameOf(kOutputFormatNames, flags.output), " and --format ",
        NameOf(report::kReportFormatNames, report_flags.format), " disagree; give one")));
  }
  auto text = [&]() -> absl::StatusOr<std::string> {
    DCS_ASSIGN_OR_RETURN(const v1::SweepResults results,
                         GetSweepResults(CoordinatorAddress(flags), report_flags.sweep_id,
                                         /*scores_only=*/true, flags.timeout));
    if (!results.study_id().empty()) {
      std::vector<coordinator::StudyTrial> trials;
      DCS_ASSIGN_OR_RETURN(const v1::StudyReport report,
                           FetchStudyReport(flags, results, report_flags.top,
                                            report_flags.options, &trials));
      if (report_flags.format == report::ReportFormat::kJson) return CommandJson(report) + "\n";
      return report::FormatStudyReport(report, report_flags.format, report_flags.top);
    }
    DCS_ASSIGN_OR_RETURN(const v1::SweepReport report,
                         report::BuildSweepReport(results, report_flags.options));
    if (report_flags.format == report::ReportFormat::kJson) return CommandJson(report) + "\n";
    return report::FormatReport(report, report_flags.format);
  }();
  if (!text.ok()) return FailCommand(text.status());
  std::cout << *text << std::flush;
  return kExitOk;
}

// What `dcs plot` writes: the figures, and the report's text in each format.
struct Plotted {
  std::vector<report::GnuplotFigure> figures;
  std::function<std::string(report::ReportFormat)> report;
};

// A plain sweep's: its figures (report/sweep_figures.h) and its table (last checkpoint,
// avg_combined).
absl::StatusOr<Plotted> PlotSweep(const v1::SweepResults& results) {
  DCS_ASSIGN_OR_RETURN(v1::SweepReport report, report::BuildSweepReport(results, {}));
  DCS_ASSIGN_OR_RETURN(std::vector<report::GnuplotFigure> figures,
                       report::SweepFigures(results, report));
  return Plotted{.figures = std::move(figures),
                 .report = [report = std::move(report)](report::ReportFormat format) {
                   return report::FormatReport(report, format);
                 }};
}

// A study sweep's: the optimisation history, the best trials' stage modes and the rank shift
// (those it has data for yet), and its report.
absl::StatusOr<Plotted> PlotStudy(const GlobalFlags& flags, const v1::SweepResults& results,
                                  int top) {
  std::vector<coordinator::StudyTrial> trials;
  DCS_ASSIGN_OR_RETURN(v1::StudyReport report,
                       FetchStudyReport(flags, results, top, {}, &trials));
  DCS_ASSIGN_OR_RETURN(
      const coordinator::StudyRecord study,
      ConnectStudies(CoordinatorAddress(flags), flags.timeout)->Get(results.study_id()));
  Plotted plotted;
  for (absl::StatusOr<report::GnuplotFigure> figure :
       {report::StudyHistoryFigure(study, trials), report::StudyStageModesFigure(report),
        report::StudyRankShiftFigure(report)}) {
    if (figure.ok()) {
      plotted.figures.push_back(*std::move(figure));
    } else if (!absl::IsFailedPrecondition(figure.status())) {  // no data for it yet
      return figure.status();
    }
  }
  plotted.report = [report = std::move(report), top](report::ReportFormat format) {
    return report::FormatStudyReport(report, format, top);
  };
  return plotted;
}

// The report (also as CSV, LaTeX and Markdown beside it), every figure with its data and script,
// and index.html, in `plot.out` (default <data-dir>/reports/<sweep id>); returns index.html's
// path.
absl::StatusOr<std::string> Plot(const GlobalFlags& flags, const PlotFlags& plot) {
  // A study's figures read the scores only; a sweep's, every context's returns.
  DCS_ASSIGN_OR_RETURN(const v1::GetSweepResponse sweep,
                       GetSweep(CoordinatorAddress(flags), plot.sweep_id, flags.timeout));
  DCS_ASSIGN_OR_RETURN(const v1::SweepResults results,
                       GetSweepResults(CoordinatorAddress(flags), plot.sweep_id,
                                       /*scores_only=*/!sweep.sweep().study_id().empty(),
                                       flags.timeout));
  DCS_ASSIGN_OR_RETURN(const Plotted plotted, results.study_id().empty()
                                                  ? PlotSweep(results)
                                                  : PlotStudy(flags, results, plot.top));
  const std::string out =
      plot.out.empty() ? absl::StrCat(flags.data_dir, "/reports/", plot.sweep_id) : plot.out;
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (error) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot create ", out, ": ", error.message()));
  }
  for (const report::GnuplotFigure& figure : plotted.figures) {
    DCS_ASSIGN_OR_RETURN(const RenderedFigure rendered, RenderFigure(figure, plot.format, out));
    std::cerr << "dcs: drew " << rendered.path << std::endl;
    if (!rendered.gnuplot_output.empty()) std::cerr << rendered.gnuplot_output << std::endl;
  }
  for (const auto& [format, file] : {std::pair{report::ReportFormat::kCsv, "report.csv"},
                                     std::pair{report::ReportFormat::kLatex, "report.tex"},
                                     std::pair{report::ReportFormat::kMarkdown, "report.md"}}) {
    DCS_RETURN_IF_ERROR(WriteFileAtomically(absl::StrCat(out, "/", file), plotted.report(format)));
  }
  const std::string index = absl::StrCat(out, "/index.html");
  DCS_RETURN_IF_ERROR(WriteFileAtomically(
      index, report::SweepIndexHtml(absl::StrCat(results.name(), " (", results.sweep_id(), ")"),
                                    plotted.report(report::ReportFormat::kHtml), plotted.figures,
                                    plot.format)));
  return index;
}

int PlotCommand(const GlobalFlags& flags, const PlotFlags& plot) {
  absl::StatusOr<std::string> index = Plot(flags, plot);
  if (!index.ok()) return FailCommand(index.status());
  std::cout << index.value() << std::endl;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddReportCommands(CLI::App& dcs, const GlobalFlags& flags) {
  auto report_flags = std::make_shared<ReportFlags>();
  CLI::App* report = dcs.add_subcommand(
      "report", "A sweep's table, as the paper's: IQM [Q1, Q3] across seeds per condition and "
                "mode, static first, the best marked, bootstrap intervals, and the probability "
                "of improvement over static");
  report->add_option("sweep", report_flags->sweep_id, "the sweep's id, e.g. sweep-1")
      ->required();
  AddChoiceOption(*report, "--checkpoint", &report_flags->options.checkpoint,
                  ChoicesOf(report::kReportCheckpointNames),
                  "last (the paper's primary result) or best (best-anytime avg_combined; every "
                  "metric read at that same evaluation)");
  AddChoiceOption(*report, "--split", &report_flags->options.split,
                  ChoicesOf(report::kReportSplitNames),
                  "the score: avg_combined over every context, or one split's mean");
  report_flags->format_option =
      AddChoiceOption(*report, "--format", &report_flags->format,
                      ChoicesOf(report::kReportFormatNames),
                      "table, md, csv, json, latex (booktabs) or html (default: -o's format)");
  report->add_option("--resamples", report_flags->options.bootstrap_resamples,
                     "bootstrap resamples of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(1, 1'000'000));
  report->add_option("--bootstrap-seed", report_flags->options.bootstrap_seed,
                     "the bootstrap's seed (the same sweep and seed give the same report)")
      ->capture_default_str();
  report->add_option("--top", report_flags->top,
                     "a study sweep's: how many of the best trials are shown, and whose stage "
                     "modes are counted")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  auto plot_flags = std::make_shared<PlotFlags>();
  CLI::App* plot = dcs.add_subcommand(
      "plot", "Draw a sweep's figures with gnuplot (learning curves, per-context returns, the "
              "family heatmap, performance profiles), each beside its CSV and script, and an "
              "index.html with the report's table; prints index.html's path");
  plot->add_option("sweep", plot_flags->sweep_id, "the sweep's id, e.g. sweep-1")->required();
  AddOutDirectory(*plot, &plot_flags->out,
                  "the directory to write (default: <data-dir>/reports/<sweep id>)");
  AddChoiceOption(*plot, "--format", &plot_flags->format, ChoicesOf(report::kFigureFormatNames),
                  "svg, png or pdf");
  plot->add_option("--top", plot_flags->top,
                   "a study sweep's: how many of the best trials the stage-mode heatmap counts")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);

  return {
      {report, [&flags, report_flags] { return ReportCommand(flags, *report_flags); },
       kEveryFormat},
      {plot, [&flags, plot_flags] { return PlotCommand(flags, *plot_flags); }},
  };
}

}  // namespace dcs::services::cli
