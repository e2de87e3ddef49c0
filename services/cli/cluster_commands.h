// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_CLUSTER_COMMANDS_H_
#define DCS_SERVICES_CLI_CLUSTER_COMMANDS_H_

// `dcs up`, `down`, `status` and `health`: the local cluster (services/cli/local_cluster.h)
// and the health of running servers.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddClusterCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_CLUSTER_COMMANDS_H_
