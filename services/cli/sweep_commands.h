// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_SWEEP_COMMANDS_H_
#define DCS_SERVICES_CLI_SWEEP_COMMANDS_H_

// `dcs submit SPEC [--watch] [--dry-run]`, `dcs sweeps`, `dcs sweeps watch|cancel|retry SWEEP`
// (also `dcs watch|cancel|retry SWEEP`) and `dcs sweeps rm SWEEP...`: sweeps on the coordinator
// at --addr (default: the local cluster).
// `submit` prints the sweep's id and returns at once unless --watch, which follows the sweep
// to its end and exits with its outcome (0 completed, 1 failed or cancelled), as `watch` does.

#include <vector>

#include <CLI/CLI.hpp>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddSweepCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_SWEEP_COMMANDS_H_
