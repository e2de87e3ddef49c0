// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <ATen/Parallel.h>
#include <c10/util/Exception.h>
#include <dlfcn.h>
#include <torch/version.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"

namespace dcs::learner {

absl::Status PinTorchThreads(int threads) {
  if (threads < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("torch threads must be at least 1, got ", threads));
  }
  // libtorch reports misuse with c10::Error; no exception leaves this library.
  try {
    // Inter-op first: it is the call that can be refused, and a refused call changes nothing.
    at::set_num_interop_threads(threads);
    at::set_num_threads(threads);
  } catch (const c10::Error& e) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot size libtorch's thread pools: ", e.what_without_backtrace()));
  }
  return absl::OkStatus();
}

std::vector<LibraryVersion> LibraryVersions() {
  std::vector<LibraryVersion> versions = {{"libtorch", TORCH_VERSION}};
  if (const std::string core = BlasCoreName(); !core.empty()) {
    versions.push_back({"openblas core", core});
  }
  return versions;
}

std::string BlasCoreName() {
  // Looked up rather than linked: libtorch reaches OpenBLAS through the libblas.so.3
  // alternative, which may be another BLAS.
  using CoreName = char* (*)();
  const auto core_name = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  return core_name == nullptr ? "" : core_name();
}

std::optional<std::string> BetterBlasCore() {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr || BlasCoreName() != "Prescott") {
    return std::nullopt;
  }
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq")) {
    return "SkylakeX";
  }
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
  return std::nullopt;
}

void RestartWithBestBlasKernels(absl::FunctionRef<void(absl::string_view)> note) {
  const std::optional<std::string> core = BetterBlasCore();
  if (!core.has_value()) return;
  absl::StatusOr<std::string> command_line = ReadFile("/proc/self/cmdline");
  if (!command_line.ok()) {
    note(absl::StrCat("cannot restart with OPENBLAS_CORETYPE=", *core, " (",
                      command_line.status().message(), "); going on with OpenBLAS's generic "
                      "kernels"));
    return;
  }
  std::vector<std::string> words = absl::StrSplit(*command_line, '\0', absl::SkipEmpty());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  note(absl::StrCat("OpenBLAS does not recognise this CPU and chose its generic kernels; "
                    "restarting with OPENBLAS_CORETYPE=",
                    *core, " (set OPENBLAS_CORETYPE to choose)"));
  setenv("OPENBLAS_CORETYPE", core->c_str(), /*overwrite=*/1);
  execv("/proc/self/exe", argv.data());
  note(absl::StrCat("cannot restart (", std::strerror(errno),
                    "); going on with OpenBLAS's generic kernels"));
}

}  // namespace dcs::learner
