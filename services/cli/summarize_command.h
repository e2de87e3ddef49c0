// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_SUMMARIZE_COMMAND_H_
#define DCS_SERVICES_CLI_SUMMARIZE_COMMAND_H_

// `dcs summarize RUN_DIR...`: the paper's per-run scores (last and best-anytime avg_combined)
// of finished runs, and across them IQM [Q1, Q3] with a 95% stratified-bootstrap interval
// (report/runs_summary.h): the numbers of one row of the paper's tables from a set of
// seeds.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddSummarizeCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_SUMMARIZE_COMMAND_H_
