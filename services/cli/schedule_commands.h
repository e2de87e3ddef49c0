// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_SCHEDULE_COMMANDS_H_
#define DCS_SERVICES_CLI_SCHEDULE_COMMANDS_H_

// `dcs schedule preview`: context trajectories of schedules over a few episodes, as CSV and as
// the paper's appendix figure (report/schedule_preview.h), drawn by gnuplot
// (services/cli/figure_render.h): `--svg FILE` writes FILE with STEM.gp and STEM.csv beside it.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddScheduleCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_SCHEDULE_COMMANDS_H_
