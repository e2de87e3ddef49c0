// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_TORCH_COMMANDS_H_
#define DCS_SERVICES_CLI_TORCH_COMMANDS_H_

// The part of `dcs` commands that needs libtorch: training in this process, and reading a
// trained policy (`eval`, `play`, `export`: services/cli/policy_commands.h). Two programs share
// every command file and differ only here: `dcs-train` links the real thing
// (torch_commands.cc); `dcs` links torch_handover.cc, which hands the invocation to `dcs-train`
// beside it (exec, same arguments, the pinned numeric kernels set), so that `dcs`, without
// libtorch, starts at once and only training pays libtorch's start-up, once.

#include "run/run_directory.h"
#include "services/cli/cli_command.h"
#include "services/cli/policy_commands.h"

namespace dcs::services::cli {

// `dcs train` in this process: trains `request` (a new run, or with `resume` the stored one),
// keeping `keep` checkpoints; prints progress and the summary. Returns the exit code.
int TrainInProcess(const run::RunRequest& request, bool resume, int keep,
                   const GlobalFlags& global);

// `dcs eval`, `dcs play` and `dcs export`. Each returns the exit code.
int EvaluateInProcess(const EvalFlags& flags, const GlobalFlags& global);
int PlayInProcess(const PlayFlags& flags, const GlobalFlags& global);
int ExportInProcess(const ExportFlags& flags, const GlobalFlags& global);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_TORCH_COMMANDS_H_
