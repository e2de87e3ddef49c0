// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_CLI_COMMAND_H_
#define DCS_SERVICES_CLI_CLI_COMMAND_H_

// The commands of the `dcs` client: each command file adds its subcommands to the command line
// and says what runs when one is chosen (services/cli/dcs_main.cc lists the files and
// dispatches); and the flag values several commands parse. Confined to main's thread.

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "services/auth.h"
#include "services/cli/command_output.h"

namespace dcs::services::cli {

// Flags every `dcs` command may use.
struct GlobalFlags {
  std::string addr;  // --addr or DCS_ADDR
  std::string data_dir;  // --data-dir or DCS_DATA_DIR, else FindDataDir (local_cluster.h)
  std::string token_file;  // --token-file or DCS_TOKEN_FILE
  TlsFiles tls;            // --tls-cert, --tls-key, --tls-ca, --tls-server-name
  absl::Duration timeout = absl::Seconds(5);
  OutputFormat output = OutputFormat::kTable;
  // This invocation's arguments, argv[0] first: a command may hand them to another program
  // (services/cli/torch_commands.h).
  std::vector<std::string> invocation;
};

// Prints `status` as `dcs`'s one error line and returns the exit code it maps to. An
// UNAVAILABLE status (no server answered) ends with the hint SetUnavailableHint gave.
int FailCommand(const absl::Status& status);

// What FailCommand adds when no server answered: how to get one (start the local cluster, name
// a coordinator). Set by main before the command runs; empty (the default) adds nothing. Not
// thread-safe: for main.
void SetUnavailableHint(std::string hint);

struct CliCommand {
  CLI::App* app;            // owned by the parent CLI::App
  std::function<int()> run;  // returns the exit code (services/exit_codes.h)
  // The formats of -o it prints its data in; `dcs` refuses another before it runs. Table
  // alone for a command that prints no data, or only words for people.
  std::vector<OutputFormat> formats = {OutputFormat::kTable};
};

inline const std::vector<OutputFormat> kEveryFormat = {OutputFormat::kTable, OutputFormat::kJson,
                                                       OutputFormat::kCsv};
inline const std::vector<OutputFormat> kTableOrJson = {OutputFormat::kTable, OutputFormat::kJson};

// What each command file provides: adds its commands to `dcs`. `flags` outlives them.
using AddCommandsFunction = std::vector<CliCommand> (*)(CLI::App& dcs, const GlobalFlags& flags);

// The command line's one convention for what a command reads and writes:
// - what it acts on (a config, a spec, a run, a sweep, a study) is a positional argument; a flag
//   that once named it (`train --config FILE`) stays as its alias;
// - `--out` is a directory (shown as `--out DIR`) where the command writes several files, and a
//   file (`--out FILE`) where it writes one artifact (a video, a state dict, a backup, a CSV),
//   with anything it writes beside that file named in `help`.
CLI::Option* AddOutDirectory(CLI::App& command, std::string* out, std::string help);
CLI::Option* AddOutFile(CLI::App& command, std::string* out, std::string help);

// Comma-separated finite numbers ("0.35,0.75"). A UsageError (services/exit_codes.h) naming
// `flag` and the bad entry.
absl::StatusOr<std::vector<double>> ParseNumberList(absl::string_view text,
                                                    absl::string_view flag);

// name=value assignments of a repeatable flag (`--set length=1.3`), by name. A UsageError
// naming `flag` for one without '=', a value that is not a finite number, or a name given
// twice.
absl::StatusOr<std::map<std::string, double>> ParseAssignments(
    const std::vector<std::string>& assignments, absl::string_view flag);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_CLI_COMMAND_H_
