// Copyright 2026 The DCS Authors.
//
// dcs: the DCS command-line client. `dcs --help` lists the commands, `dcs <command> --help`
// describes each; README.md shows them in use. Built twice: `dcs`, without libtorch, and
// `dcs-train`, with it, to which `dcs` hands the commands that need it
// (services/cli/torch_commands.h). stdout carries data only; progress and errors
// go to stderr. Exit codes: README.md.

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/algorithm/container.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "services/auth.h"
#include "services/cli/backup_command.h"
#include "services/cli/cli_command.h"
#include "services/cli/cluster_client.h"
#include "services/cli/cluster_commands.h"
#include "services/cli/env_commands.h"
#include "services/cli/local_cluster.h"
#include "services/cli/logs_command.h"
#include "services/cli/policy_commands.h"
#include "services/cli/report_commands.h"
#include "services/cli/runs_commands.h"
#include "services/cli/schedule_commands.h"
#include "services/cli/study_commands.h"
#include "services/cli/summarize_command.h"
#include "services/cli/sweep_commands.h"
#include "services/cli/train_command.h"
#include "services/cli/version_command.h"
#include "services/command_line.h"
#include "services/exit_codes.h"
#include "services/log.h"

namespace dcs::services::cli {
namespace {

// Every command file of `dcs`, in the order `dcs --help` lists their commands.
constexpr AddCommandsFunction kCommandFiles[] = {
    AddClusterCommands,  AddLogsCommand,   AddVersionCommand, AddEnvCommands,
    AddScheduleCommands, AddTrainCommand,  AddRunsCommands,   AddSweepCommands,
    AddReportCommands,   AddSummarizeCommand, AddStudyCommands, AddPolicyCommands,
    AddBackupCommand,
};

// "table, json or csv": the formats of -o `command` prints.
std::string FormatNames(const CliCommand& command) {
  std::string names;
  for (size_t i = 0; i < command.formats.size(); ++i) {
    if (i > 0) names += i + 1 == command.formats.size() ? " or " : ", ";
    absl::StrAppend(&names, NameOf(kOutputFormatNames, command.formats[i]));
  }
  return names;
}

int Main(int argc, char** argv) {
  ConfigureLogging({.component = "dcs"});
  CLI::App app("dcs: dynamic context scheduling for reinforcement learning, as a service", "dcs");
  app.require_subcommand(0, 1);
  app.fallthrough();  // global flags may follow the command
  GlobalFlags flags{.invocation = {argv, argv + argc}};
  app.add_option("--addr", flags.addr,
                 "a server's gRPC address host:port (default: the local cluster's "
                 "coordinator, else 127.0.0.1:50051)")
      ->envname("DCS_ADDR");
  CLI::Option* data_dir =
      app.add_option("--data-dir", flags.data_dir,
                     "where `dcs up` keeps logs and cluster state (default: $DCS_DATA_DIR, else "
                     "the nearest dcs-data, here or in a parent directory, that records a "
                     "cluster `dcs up` started, else ./dcs-data)")
          ->envname("DCS_DATA_DIR");
  app.add_option("--token-file", flags.token_file,
                 "the cluster's bearer token (default: $DCS_TOKEN, else the local cluster's "
                 "when calling its coordinator)")
      ->envname("DCS_TOKEN_FILE");
  AddTlsFlags(app, flags.tls);
  AddDurationOption(app, "--timeout", &flags.timeout, "deadline of each call to a server");
  AddChoiceOption(app, "-o,--output", &flags.output, ChoicesOf(kOutputFormatNames),
                  "table, json (JSON Lines, for scripts) or csv, where the command prints data");

  std::vector<CliCommand> commands;
  for (AddCommandsFunction add : kCommandFiles) {
    for (CliCommand& command : add(app, flags)) commands.push_back(std::move(command));
  }
  // Each command's help says what it prints (CliConventionTest runs each that prints json).
  for (const CliCommand& command : commands) {
    if (command.formats.size() > 1) {
      command.app->footer(absl::StrCat("Prints its data as -o ", FormatNames(command), "."));
    }
  }

  if (std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  const bool data_dir_named = data_dir->count() > 0;  // by the flag or DCS_DATA_DIR
  if (!data_dir_named) {
    std::error_code no_cwd;  // a removed working directory: ./dcs-data, which will not do either
    flags.data_dir = FindDataDir(std::filesystem::current_path(no_cwd));
  }
  if (flags.addr.empty() && !ReadClusterState(flags.data_dir).ok()) {
    SetUnavailableHint(absl::StrCat(
        "no local cluster is recorded in ", flags.data_dir,
        data_dir_named ? "" : " (looked here and in the parent directories)",
        ": start one with `dcs up`, or name a coordinator with --addr or DCS_ADDR"));
  }
  absl::StatusOr<std::string> token = ClientToken(flags);
  if (!token.ok()) return FailCommand(token.status());
  SetClusterToken(*std::move(token));
  if (absl::Status tls = CheckTlsFiles(flags.tls); !tls.ok()) return FailCommand(tls);
  SetClusterTls(flags.tls);
  for (const CliCommand& command : commands) {
    if (!command.app->parsed()) continue;
    if (absl::c_linear_search(command.formats, flags.output)) return command.run();
    PrintError("dcs", absl::StrCat("-o ", NameOf(kOutputFormatNames, flags.output), ": `",
                                   CommandPath(*command.app), "` prints ", FormatNames(command),
                                   " (see --help)"));
    return kExitUsage;
  }
  // Checked here rather than by CLI11, which would report it before an unknown flag.
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
  PrintError("dcs", absl::StrCat("a command is required: ", absl::StrJoin(names, ", "),
                                 " (see --help)"));
  return kExitUsage;
}

}  // namespace
}  // namespace dcs::services::cli

int main(int argc, char** argv) { return dcs::services::cli::Main(argc, argv); }
