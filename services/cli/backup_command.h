// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_BACKUP_COMMAND_H_
#define DCS_SERVICES_CLI_BACKUP_COMMAND_H_

// `dcs backup --out FILE`: a consistent copy of the running coordinator's store (SQLite's online
// backup, taken by the coordinator and streamed here), written to FILE atomically once whole and
// checked. Prints the file, its size and what it holds. The runs' files (checkpoints, evaluation
// logs) are not in it: README, Backups, says what a restore needs.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddBackupCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_BACKUP_COMMAND_H_
