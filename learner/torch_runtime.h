// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TORCH_RUNTIME_H_
#define DCS_LEARNER_TORCH_RUNTIME_H_

// Process-wide settings of the numeric libraries behind libtorch. Every process that trains or
// updates calls RestartWithBestBlasKernels first thing in main, then PinTorchThreads. Not
// thread-safe: call from main before any torch work.
//
// DESIGN.md §4: with libtorch pinned to one thread per run, the same sweep gives the same
// report bit for bit however many learners share a machine.

#include <optional>
#include <string>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "common/library_version.h"

namespace dcs::learner {

// Sets libtorch's intra-op and inter-op thread pools to `threads` each.
// Returns INVALID_ARGUMENT if `threads` < 1, and FAILED_PRECONDITION if libtorch has already
// started its inter-op pool (it can be sized only once per process).
absl::Status PinTorchThreads(int threads);

// libtorch, as compiled against, and the OpenBLAS core its matrix products run on (results
// are bit-for-bit reproducible only on the same core).
std::vector<LibraryVersion> LibraryVersions();

// The OpenBLAS core in use ("SkylakeX", "Haswell", ...), or empty if libtorch's BLAS is not
// OpenBLAS.
std::string BlasCoreName();

// OpenBLAS picks its kernels from the CPU's model; one it does not know (OpenBLAS 0.3.21, as in
// Debian 12, predates Emerald Rapids Xeons) gets its generic SSE3 "Prescott" kernels, which make
// PPO updates about 1.3x slower than the AVX-512 ones. When that happened on a CPU with AVX-512
// (or AVX2 and FMA), the core to ask for with OPENBLAS_CORETYPE: "SkylakeX" (or "Haswell");
// otherwise, or when OPENBLAS_CORETYPE is already set, nullopt.
std::optional<std::string> BetterBlasCore();

// When BetterBlasCore names a core, runs this program again, with the same arguments and
// OPENBLAS_CORETYPE set to it (OpenBLAS reads it once, when the program loads, so it cannot be
// set later); `note` gets one line saying so first. Returns when there is nothing to do, or if
// the restart failed: then `note` gets the reason, and the process goes on with the generic
// kernels (only slower).
void RestartWithBestBlasKernels(absl::FunctionRef<void(absl::string_view)> note);

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TORCH_RUNTIME_H_
