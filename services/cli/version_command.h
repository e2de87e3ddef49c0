// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_VERSION_COMMAND_H_
#define DCS_SERVICES_CLI_VERSION_COMMAND_H_

// `dcs version`: this build of DCS and the third-party libraries it computes with, as workers
// report theirs when they register (bit-for-bit reproducibility needs the same ones).

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddVersionCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_VERSION_COMMAND_H_
