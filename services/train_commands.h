// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_TRAIN_COMMANDS_H_
#define DCS_SERVICES_TRAIN_COMMANDS_H_

// `dcs train --config run.yaml`: one training run in this process (learner/training_run.h),
// with a progress line on a terminal, checkpoints and the evaluation log in the run's output
// directory, and `--resume` to continue a stopped run. Ctrl-C stops after the current update,
// with a checkpoint to resume from.
//
// `dcs summarize RUN_DIR...`: the paper's per-run scores (last and best-anytime avg_combined)
// of finished runs, and across them IQM [Q1, Q3] with a 95% stratified-bootstrap interval
// (coordinator/iqm.h): the numbers of one row of the paper's tables from a set of seeds.

#include <vector>

#include "services/cli_command.h"

namespace dcs::services {

// Adds `train` and `summarize` to `dcs`.
std::vector<CliCommand> AddTrainCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services

#endif  // DCS_SERVICES_TRAIN_COMMANDS_H_
