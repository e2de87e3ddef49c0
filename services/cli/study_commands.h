// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_STUDY_COMMANDS_H_
#define DCS_SERVICES_CLI_STUDY_COMMANDS_H_

// Ask-and-tell studies for objectives outside DCS, as Optuna 4.9's, under `dcs studies` (spelt
// as `runs` and `sweeps` are; `dcs study` is the same command):
//
//   dcs studies              a row per study: trials by state, best value, its sweep if any
//                            (also `dcs studies list`)
//   dcs studies create space.yaml [--sampler tpe|random] [--seed N]
//                      [--direction minimize|maximize] [--multivariate [--group]]
//                      [--constant-liar] [--startup-trials N] [--name NAME]
//                      [--pruner none|median|successive_halving] [pruner options]
//   dcs studies ask STUDY    {"trial": 3, "state": "running", "params": {"x": 1.5, "mode": "a"}}
//   dcs studies report STUDY TRIAL STEP VALUE   prune | continue (the study's pruner's answer)
//   dcs studies tell STUDY TRIAL VALUE   (or --state pruned|failed, and no VALUE)
//   dcs studies best STUDY   {"trial": 7, "state": "complete", "value": 0.4, "params": {...}}
//   dcs studies trials STUDY   a table of every trial (-o json: a JSON line per trial)
//   dcs studies plot STUDY [--out DIR] [--format svg|png|pdf]   the optimisation history
//
// `create` prints the study's id. A study lives on the coordinator (--addr, default the local
// cluster of `dcs up`), or, with --store FILE on every command, in a local SQLite file with no
// cluster running (the coordinator's schema). A categorical parameter prints its choice's name;
// a NaN value fails the trial.

#include <vector>

#include <CLI/CLI.hpp>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddStudyCommands(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_STUDY_COMMANDS_H_
