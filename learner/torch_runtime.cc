// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <ATen/Parallel.h>
#include <c10/util/Exception.h>
#include <dlfcn.h>
#include <torch/version.h>

#include <cstdlib>

#include "absl/strings/str_cat.h"

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

}  // namespace dcs::learner
