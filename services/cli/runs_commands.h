// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_RUNS_COMMANDS_H_
#define DCS_SERVICES_CLI_RUNS_COMMANDS_H_

// `dcs runs`: the runs of a cluster. `dcs runs` lists them (state, step, steps/s, latest
// avg_combined); `runs watch RUN` follows one to its end (run_follower.h); `runs cancel RUN`
// stops one; `runs get RUN --out DIR` downloads its files as `dcs train` lays them out; `runs rm
// RUN...` removes ended runs for good (a copy `runs get` downloaded stays).

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddRunsCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_RUNS_COMMANDS_H_
