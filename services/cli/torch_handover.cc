// Copyright 2026 The DCS Authors.
//
// torch_commands.h for `dcs`: training in process, and the commands reading trained policies,
// are handed to `dcs-train`, the same client with libtorch linked, beside this program, with
// this invocation's arguments.

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "common/exec_array.h"
#include "common/pinned_kernels.h"
#include "services/cli/torch_commands.h"

namespace dcs::services::cli {
namespace {

// Replaces this process by `dcs-train` with the same arguments, started with the pinned
// numeric kernels: were they missing, it would start libtorch, see them missing and run
// itself again to set them (learner::PinNumericKernels), paying libtorch's start-up twice.
// Returns only if that fails.
int HandOver(const GlobalFlags& global) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::string program = (self.parent_path() / "dcs-train").string();
  std::vector<std::string> arguments = global.invocation;
  arguments[0] = program;
  std::vector<std::string> environment = PinnedKernelEnvironment(environ);
  const std::vector<char*> argv = ExecArray(arguments);
  const std::vector<char*> envp = ExecArray(environment);
  execve(program.c_str(), argv.data(), envp.data());
  return FailCommand(absl::FailedPreconditionError(
      absl::StrCat("cannot run ", program, " (it trains in process): ", std::strerror(errno))));
}

}  // namespace

int TrainInProcess(const run::RunRequest& /*request*/, bool /*resume*/, int /*keep*/,
                   const GlobalFlags& global) {
  return HandOver(global);
}

int EvaluateInProcess(const EvalFlags& /*flags*/, const GlobalFlags& global) {
  return HandOver(global);
}

int PlayInProcess(const PlayFlags& /*flags*/, const GlobalFlags& global) {
  return HandOver(global);
}

int ExportInProcess(const ExportFlags& /*flags*/, const GlobalFlags& global) {
  return HandOver(global);
}

}  // namespace dcs::services::cli
