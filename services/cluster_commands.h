// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLUSTER_COMMANDS_H_
#define DCS_SERVICES_CLUSTER_COMMANDS_H_

// `dcs up`, `down`, `status`, `health` and `version`: the local cluster and the health of
// running servers.

#include <vector>

#include "services/cli_command.h"

namespace dcs::services {

// Adds the commands to `dcs`; `flags` must outlive the returned commands' runs.
std::vector<CliCommand> AddClusterCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services

#endif  // DCS_SERVICES_CLUSTER_COMMANDS_H_
