// Copyright 2026 The DCS Authors.
#include "services/cli/version_command.h"

#include "services/cli/torch_commands.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddVersionCommand(CLI::App& dcs, const GlobalFlags& flags) {
  CLI::App* version = dcs.add_subcommand("version", "Show this build and its libraries");
  return {{version, [&flags] { return ShowVersion(flags); }}};
}

}  // namespace dcs::services::cli
