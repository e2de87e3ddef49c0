// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <ATen/Parallel.h>
#include <c10/util/Exception.h>
#include <torch/version.h>

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

std::vector<LibraryVersion> LibraryVersions() { return {{"libtorch", TORCH_VERSION}}; }

}  // namespace dcs::learner
