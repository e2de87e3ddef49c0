// Copyright 2026 The DCS Authors.
#include "services/cli/command_output.h"
#include "services/cli/summarize_command.h"

#include <iostream>
#include <memory>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/text_table.h"
#include "report/runs_summary.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

std::string FormatScoreSummary(const v1::ScoreSummary& score) {
  return absl::StrFormat("%.1f [%.1f, %.1f]  (95%% CI of the IQM [%.1f, %.1f])", score.iqm(),
                         score.q1(), score.q3(), score.ci_low(), score.ci_high());
}

int RunSummarize(const std::vector<std::string>& dirs, const GlobalFlags& global) {
  absl::StatusOr<v1::RunsSummary> summary = report::SummarizeRuns(dirs);
  if (!summary.ok()) return FailCommand(summary.status());
  if (global.output == OutputFormat::kJson) {
    std::cout << CommandJson(*summary) << std::endl;
    return kExitOk;
  }
  std::vector<std::vector<std::string>> rows = {{"RUN", "SEED", "STEPS", "LAST", "BEST-ANYTIME"}};
  for (const v1::RunScore& run : summary->runs()) {
    rows.push_back({run.run(), absl::StrCat(run.seed()), absl::StrCat(run.steps()),
                    absl::StrFormat("%.1f", run.last()),
                    absl::StrFormat("%.1f", run.best_anytime())});
  }
  if (global.output == OutputFormat::kCsv) {
    std::cout << FormatRows(rows, global.output) << std::flush;
    return kExitOk;
  }
  std::cout << RenderTable(rows) << "\n"
            << "avg_combined IQM [Q1, Q3] over " << summary->runs_size() << " runs\n"
            << "  last          " << FormatScoreSummary(summary->last()) << "\n"
            << "  best-anytime  " << FormatScoreSummary(summary->best_anytime()) << std::endl;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddSummarizeCommand(CLI::App& dcs, const GlobalFlags& flags) {
  auto run_dirs = std::make_shared<std::vector<std::string>>();
  CLI::App* summarize = dcs.add_subcommand(
      "summarize", "Scores of finished runs (one condition, several seeds) and their IQM [Q1, Q3]");
  summarize->add_option("runs", *run_dirs, "the runs' directories (as dcs train --out)")
      ->required();
  return {
      {summarize, [run_dirs, &flags] { return RunSummarize(*run_dirs, flags); }, kEveryFormat}};
}

}  // namespace dcs::services::cli
