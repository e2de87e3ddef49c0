// Copyright 2026 The DCS Authors.
#include "services/cli/version_command.h"

#include <iostream>
#include <string>

#include "absl/strings/string_view.h"
#include "coordinator/library_versions.h"
#include "env/library_versions.h"
#include "learner/torch_runtime.h"
#include "services/build_info.h"
#include "services/cli/text_table.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

int RunVersion() {
  // The kernels rows show what `dcs train` computes with on this machine: the pinned ones.
  learner::PinNumericKernels(
      [](absl::string_view note) { std::cerr << "dcs: " << note << std::endl; });
  BuildInfo build = ProcessBuildInfo(coordinator::LibraryVersions());
  for (const auto& libraries : {env::LibraryVersions(), learner::LibraryVersions()}) {
    build.libraries.insert(build.libraries.end(), libraries.begin(), libraries.end());
  }
  std::vector<std::vector<std::string>> rows = {{"LIBRARY", "VERSION"}};
  for (const LibraryVersion& library : build.libraries) {
    rows.push_back({library.name, library.version});
  }
  std::cout << "dcs " << build.version << "\n\n" << RenderTable(rows) << std::flush;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddVersionCommand(CLI::App& dcs, const GlobalFlags&) {
  CLI::App* version = dcs.add_subcommand("version", "Show this build and its libraries");
  return {{version, [] { return RunVersion(); }}};
}

}  // namespace dcs::services::cli
