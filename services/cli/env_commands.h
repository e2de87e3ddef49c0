// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_ENV_COMMANDS_H_
#define DCS_SERVICES_CLI_ENV_COMMANDS_H_

// `dcs env ...`, debugging tools for the environments: `trace` (CartPole's state after every
// step of a given action sequence: how the Gymnasium comparison is checked), `rollout` (a
// baseline policy's returns over some episodes) and `render` (PNG frames of one episode).

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddEnvCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_ENV_COMMANDS_H_
