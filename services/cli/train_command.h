// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_TRAIN_COMMAND_H_
#define DCS_SERVICES_CLI_TRAIN_COMMAND_H_

// `dcs train run.yaml`: one training run in this process (learner/training_run.h),
// with a progress line on a terminal, checkpoints and the evaluation log in the run's directory
// (run/run_directory.h), and `--resume` to continue a stopped run. Ctrl-C stops after the
// current update, with a checkpoint to resume from.

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddTrainCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_TRAIN_COMMAND_H_
