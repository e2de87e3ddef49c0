// Copyright 2026 The DCS Authors.
#include "services/cli/report_commands.h"

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "coordinator/report_format.h"
#include "coordinator/sweep_figures.h"
#include "coordinator/sweep_index_html.h"
#include "coordinator/sweep_report.h"
#include "services/cli/cluster_client.h"
#include "services/cli/figure_render.h"
#include "services/cli/run_client.h"
#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

struct ReportFlags {
  std::string sweep_id;
  coordinator::ReportOptions options;
  coordinator::ReportFormat format = coordinator::ReportFormat::kTable;
};

struct PlotFlags {
  std::string sweep_id;
  std::string out;
  coordinator::FigureFormat format = coordinator::FigureFormat::kSvg;
};

// The sweep's report as `options` asks, from its results on the coordinator (only the scores a
// report reads with `scores_only`; everything, for figures, without).
absl::StatusOr<v1::SweepReport> FetchReport(const GlobalFlags& flags, const std::string& sweep_id,
                                            const coordinator::ReportOptions& options,
                                            bool scores_only, v1::SweepResults* results) {
  DCS_ASSIGN_OR_RETURN(*results, GetSweepResults(CoordinatorAddress(flags), sweep_id,
                                                 scores_only, flags.timeout));
  return coordinator::BuildSweepReport(*results, options);
}

int ReportCommand(const GlobalFlags& flags, const ReportFlags& report_flags) {
  v1::SweepResults results;
  absl::StatusOr<v1::SweepReport> report =
      FetchReport(flags, report_flags.sweep_id, report_flags.options,
                  /*scores_only=*/true, &results);
  if (!report.ok()) return FailCommand(report.status());
  std::cout << coordinator::FormatReport(*report, report_flags.format) << std::flush;
  return kExitOk;
}

// The report's table (last checkpoint, avg_combined; also as CSV and LaTeX beside it), every
// figure with its data and script, and index.html, in `plot.out`; returns index.html's path.
absl::StatusOr<std::string> Plot(const GlobalFlags& flags, const PlotFlags& plot) {
  v1::SweepResults results;
  DCS_ASSIGN_OR_RETURN(const v1::SweepReport report,
                       FetchReport(flags, plot.sweep_id, {}, /*scores_only=*/false, &results));
  DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::GnuplotFigure> figures,
                       coordinator::SweepFigures(results, report));
  std::error_code error;
  std::filesystem::create_directories(plot.out, error);
  if (error) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot create ", plot.out, ": ", error.message()));
  }
  for (const coordinator::GnuplotFigure& figure : figures) {
    DCS_ASSIGN_OR_RETURN(const RenderedFigure rendered,
                         RenderFigure(figure, plot.format, plot.out));
    std::cerr << "dcs: drew " << rendered.path << std::endl;
    if (!rendered.gnuplot_output.empty()) std::cerr << rendered.gnuplot_output << std::endl;
  }
  for (const auto& [format, file] :
       {std::pair{coordinator::ReportFormat::kCsv, "report.csv"},
        std::pair{coordinator::ReportFormat::kLatex, "report.tex"},
        std::pair{coordinator::ReportFormat::kMarkdown, "report.md"}}) {
    DCS_RETURN_IF_ERROR(WriteFileAtomically(absl::StrCat(plot.out, "/", file),
                                            coordinator::FormatReport(report, format)));
  }
  const std::string index = absl::StrCat(plot.out, "/index.html");
  DCS_RETURN_IF_ERROR(WriteFileAtomically(
      index, coordinator::SweepIndexHtml(
                 absl::StrCat(results.name(), " (", results.sweep_id(), ")"),
                 coordinator::FormatReport(report, coordinator::ReportFormat::kHtml), figures,
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
                  ChoicesOf(coordinator::kReportCheckpointNames),
                  "last (the paper's primary result) or best (best-anytime avg_combined; every "
                  "metric read at that same evaluation)");
  AddChoiceOption(*report, "--split", &report_flags->options.split,
                  ChoicesOf(coordinator::kReportSplitNames),
                  "the score: avg_combined over every context, or one split's mean");
  AddChoiceOption(*report, "--format", &report_flags->format,
                  ChoicesOf(coordinator::kReportFormatNames),
                  "table, md, csv, json, latex (booktabs) or html");
  report->add_option("--resamples", report_flags->options.bootstrap_resamples,
                     "bootstrap resamples of the intervals")
      ->capture_default_str()
      ->check(CLI::Range(1, 1'000'000));
  report->add_option("--bootstrap-seed", report_flags->options.bootstrap_seed,
                     "the bootstrap's seed (the same sweep and seed give the same report)")
      ->capture_default_str();

  auto plot_flags = std::make_shared<PlotFlags>();
  CLI::App* plot = dcs.add_subcommand(
      "plot", "Draw a sweep's figures with gnuplot (learning curves, per-context returns, the "
              "family heatmap, performance profiles), each beside its CSV and script, and an "
              "index.html with the report's table; prints index.html's path");
  plot->add_option("sweep", plot_flags->sweep_id, "the sweep's id, e.g. sweep-1")->required();
  plot->add_option("--out", plot_flags->out, "the directory to write")->required();
  AddChoiceOption(*plot, "--format", &plot_flags->format,
                  ChoicesOf(coordinator::kFigureFormatNames), "svg, png or pdf");

  return {
      {report, [&flags, report_flags] { return ReportCommand(flags, *report_flags); }},
      {plot, [&flags, plot_flags] { return PlotCommand(flags, *plot_flags); }},
  };
}

}  // namespace dcs::services::cli
