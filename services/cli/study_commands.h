// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_STUDY_COMMANDS_H_
#define DCS_SERVICES_CLI_STUDY_COMMANDS_H_

// Ask-and-tell studies for objectives outside DCS, as Optuna's (shared/spec/tpe.md):
//
//   dcs study create --space space.yaml [--sampler tpe|random] [--seed N]
//                    [--direction minimize|maximize] [--multivariate [--group]]
//                    [--constant-liar] [--startup-trials N] [--name NAME] --store FILE
//   dcs study ask STUDY --store FILE          {"trial": 3, "params": {"x": 1.5, "mode": "a"}}
//   dcs study tell STUDY TRIAL VALUE --store FILE   (or --state pruned|failed, no VALUE)
//   dcs study best STUDY --store FILE         {"trial": 7, "value": 0.4, "params": {...}}
//
// `create` prints the study's id. The study lives in the SQLite file --store (created if
// missing; the coordinator's schema, so a coordinator could open it), with no cluster running.
// A categorical parameter prints its choice's name; a NaN value fails the trial.

#include <vector>

#include <CLI/CLI.hpp>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddStudyCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_STUDY_COMMANDS_H_
