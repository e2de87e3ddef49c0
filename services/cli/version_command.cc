// Copyright 2026 The DCS Authors.
#include "services/cli/version_command.h"

#include <iostream>
#include <string>
#include <vector>

#include "common/library_version.h"
#include "common/pinned_kernels.h"
#include "common/text_table.h"
#include "coordinator/library_versions.h"
#include "env/library_versions.h"
#include "services/build_info.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {
namespace {

int ShowVersion() {
  std::vector<LibraryVersion> own = coordinator::LibraryVersions();
  for (const LibraryVersion& library : env::LibraryVersions()) own.push_back(library);
  own.push_back(CompiledLibtorchVersion());
  const BuildInfo build = ProcessBuildInfo(own);
  std::vector<std::vector<std::string>> libraries = {{"LIBRARY", "VERSION"}};
  for (const LibraryVersion& library : build.libraries) {
    libraries.push_back({library.name, library.version});
  }
  std::vector<std::vector<std::string>> kernels = {{"PINNED KERNEL SETTING", "VALUE"}};
  for (const KernelVariable& variable : kPinnedKernels) {
    kernels.push_back({variable.name, variable.value});
  }
  std::cout << "dcs " << build.version << "\n\n"
            << RenderTable(libraries) << "\n"
            << RenderTable(kernels) << std::flush;
  return kExitOk;
}

}  // namespace

std::vector<CliCommand> AddVersionCommand(CLI::App& dcs, const GlobalFlags& /*flags*/) {
  CLI::App* version = dcs.add_subcommand(
      "version",
      "Show this build, its libraries (libtorch as compiled against) and the numeric kernels "
      "every process that trains pins");
  return {{version, ShowVersion}};
}

}  // namespace dcs::services::cli
