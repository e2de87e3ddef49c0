// Copyright 2026 The DCS Authors.
//
// dcs: the DCS command-line client. `dcs <command> --help` describes each command.
//   dcs up [-d] [--actors N]   start a local cluster (coordinator, learner, actors) on loopback
//   dcs down                   stop the local cluster started from --data-dir
//   dcs status [-o json]       the coordinator's workers: role, address, state, last heartbeat
//   dcs health --addr H:P      exit 0 if the server is SERVING (for probes and scripts)
//   dcs version                this build and the libraries it links
//   dcs env trace ...          an environment's state after every step of an action sequence
//   dcs schedule preview ...   schedule trajectories as CSV and the paper's appendix figure
//   dcs train --config F       one training run in this process, with the paper's evaluation
//   dcs summarize DIR...       finished runs' scores and their IQM [Q1, Q3] across seeds
// stdout carries data only; progress and errors go to stderr. Exit codes: README.md.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "services/cli_command.h"
#include "services/cluster_commands.h"
#include "services/command_line.h"
#include "services/env_commands.h"
#include "services/exit_codes.h"
#include "services/log.h"
#include "services/train_commands.h"

namespace dcs::services {
namespace {

int Main(int argc, char** argv) {
  ConfigureLogging({.component = "dcs"});
  CLI::App app("dcs: dynamic context scheduling for reinforcement learning, as a service", "dcs");
  app.require_subcommand(0, 1);
  app.fallthrough();  // global flags may follow the command
  GlobalFlags flags;
  app.add_option("--addr", flags.addr,
                 "a server's gRPC address host:port (default: the local cluster's "
                 "coordinator, else 127.0.0.1:50051)")
      ->envname("DCS_ADDR");
  app.add_option("--data-dir", flags.data_dir, "where `dcs up` keeps logs and cluster state")
      ->capture_default_str();
  AddDurationOption(app, "--timeout", &flags.timeout, "deadline of each call to a server");
  AddChoiceOption(app, "-o,--output", &flags.output, OutputFormatNames(),
                  "table, or json (for scripts)");

  std::vector<CliCommand> commands = AddClusterCommands(app, flags);
  for (CliCommand& command : AddEnvCommands(app)) commands.push_back(std::move(command));
  for (CliCommand& command : AddTrainCommands(app, flags)) commands.push_back(std::move(command));

  if (std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  for (const CliCommand& command : commands) {
    if (command.app->parsed()) return command.run();
  }
  // Checked here rather than by CLI11, which would report it before an unknown flag.
  PrintError("dcs", "a command is required: up, down, status, health, version, env, "
                    "schedule, train or summarize (see --help)");
  return kExitUsage;
}

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) { return dcs::services::Main(argc, argv); }
