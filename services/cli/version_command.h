// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_VERSION_COMMAND_H_
#define DCS_SERVICES_CLI_VERSION_COMMAND_H_

// `dcs version`: this build of DCS, the third-party libraries its programs compute with (as
// workers report theirs when they register: bit-for-bit reproducibility needs the same ones),
// and the numeric kernels every process that trains pins (common/pinned_kernels.h). Without
// loading libtorch: its version is the one the trainers were compiled against, and the kernels
// are the pinned settings; what a learner runs with, it reports itself (`dcs status`).

#include <vector>

#include "services/cli/cli_command.h"

namespace dcs::services::cli {

std::vector<CliCommand> AddVersionCommand(CLI::App& dcs, const GlobalFlags& flags);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_VERSION_COMMAND_H_
