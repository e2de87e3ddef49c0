// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_ENV_COMMANDS_H_
#define DCS_SERVICES_ENV_COMMANDS_H_

// `dcs env trace` (an environment's state after every step of a given action sequence: a
// debugging tool, and how the Gymnasium comparison is checked) and `dcs schedule preview`
// (context trajectories of schedules, as CSV and as the paper's appendix figure).

#include <vector>

#include "services/cli_command.h"

namespace dcs::services {

// Adds `env trace` and `schedule preview` to `dcs`.
std::vector<CliCommand> AddEnvCommands(CLI::App& dcs);

}  // namespace dcs::services

#endif  // DCS_SERVICES_ENV_COMMANDS_H_
