// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_REPORT_COMMANDS_H_
#define DCS_SERVICES_CLI_REPORT_COMMANDS_H_

// `dcs report SWEEP [--checkpoint last|best] [--split combined|id|ood_low|ood_high]
// [--format table|md|csv|json|latex|html]` prints a sweep's table (report/sweep_report.h,
// report/report_format.h); `dcs plot SWEEP --out DIR [--format svg|png|pdf]` draws its
// figures with gnuplot (report/sweep_figures.h), each beside its data and script, and
// writes DIR/index.html showing the table and every figure. Both read the sweep's completed
// runs from the coordinator at --addr; a sweep still running is reported as far as it got.

#include <vector>

#include <CLI/CLI.hpp>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddReportCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_REPORT_COMMANDS_H_
