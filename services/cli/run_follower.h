// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_RUN_FOLLOWER_H_
#define DCS_SERVICES_CLI_RUN_FOLLOWER_H_

// Following a run on a cluster to its end, as `dcs train --cluster` and `dcs runs watch` do:
// progress lines while it trains; Ctrl-C detaches (the run goes on); at the end its files are
// downloaded into `out_dir` and the same summary as `dcs train` in one process is printed.
// Confined to main's thread (it installs SIGINT and SIGTERM handlers).

#include <string>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

// Returns the exit code: 0 when the run completed; 130 when detached; 1 when it failed or was
// cancelled; others as FailCommand.
int FollowRun(const std::string& address, const std::string& run_id, const std::string& out_dir,
              const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_RUN_FOLLOWER_H_
