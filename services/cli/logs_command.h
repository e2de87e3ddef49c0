// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_LOGS_COMMAND_H_
#define DCS_SERVICES_CLI_LOGS_COMMAND_H_

// `dcs logs [PROCESS] [-n LINES] [-f]`: the local cluster's logs, each process's stdout and
// stderr as `dcs up` keeps them in the data directory (services/cli/local_cluster.h). Without a
// process, lists the processes that have a log; with one, prints its log (its last LINES with
// -n) and, with -f, what the process writes next until Ctrl-C. A process with no log is
// NOT_FOUND, naming the logs there and the closest name.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddLogsCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_LOGS_COMMAND_H_
