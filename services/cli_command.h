// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_COMMAND_H_
#define DCS_SERVICES_CLI_COMMAND_H_

// The commands of the `dcs` client: each command file adds its subcommands to the command line
// and says what runs when one is chosen (services/dcs_main.cc dispatches). Confined to main's
// thread.

#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "services/status_format.h"

namespace dcs::services {

// Flags every `dcs` command may use.
struct GlobalFlags {
  std::string addr;  // --addr or DCS_ADDR
  std::string data_dir = "dcs-data";
  absl::Duration timeout = absl::Seconds(5);
  OutputFormat output = OutputFormat::kTable;
};

// Prints `status` as `dcs`'s one error line and returns the exit code it maps to.
int FailCommand(const absl::Status& status);

struct CliCommand {
  CLI::App* app;            // owned by the parent CLI::App
  std::function<int()> run;  // returns the exit code (services/exit_codes.h)
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_CLI_COMMAND_H_
