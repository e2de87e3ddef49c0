// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TORCH_RUNTIME_H_
#define DCS_LEARNER_TORCH_RUNTIME_H_

// Process-wide settings of libtorch and the numeric libraries behind it. Every process that
// trains or updates calls PinNumericKernels first thing in main, then PinTorchThreads. Not
// thread-safe: call from main before any torch work.
//
// docs/architecture.md §8: with libtorch pinned to one thread per run and its numeric kernels
// pinned to one choice, the same sweep gives the same report bit for bit however many learners
// share a machine, on any x86-64 machine with AVX2 and FMA, Intel or AMD.

#include <string>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "common/library_version.h"
#include "common/pinned_kernels.h"

namespace dcs::learner {

// Sets libtorch's intra-op and inter-op thread pools to `threads` each.
// Returns INVALID_ARGUMENT if `threads` < 1, and FAILED_PRECONDITION if libtorch has already
// started its inter-op pool (it can be sized only once per process).
absl::Status PinTorchThreads(int threads);

// The entries of kPinnedKernels (common/pinned_kernels.h) whose environment variable is unset
// or holds another value. Empty when this process was started with the pinned kernels.
std::vector<KernelVariable> UnpinnedKernelVariables();

// Pins the numeric kernels of this process (common/pinned_kernels.h): if
// UnpinnedKernelVariables is not empty, runs this program again, from /proc/self/exe with the
// same arguments, with those variables set, silently (every run's summary and a learner's
// registration name the kernels). The call does not return then. DCS's own ways of starting a
// trainer (`dcs train`, `dcs up`, the deployments) set the variables, so this restart, which
// pays libtorch's start-up twice, is for a trainer started by hand.
// Returns when the kernels are pinned, or when the restart failed: then `note` gets a line
// saying why and that results will not match other machines' bit for bit, and the process goes
// on with the kernels its libraries chose. (Every DCS program runs on a CPU with the pinned
// kernels' AVX2 and FMA: common/cpu_requirement.cc.)
void PinNumericKernels(absl::FunctionRef<void(absl::string_view)> note);

// The lock every call into BLAS from learner code (the orthogonal initialisation) holds, as
// `absl::MutexLockMaybe blas(BlasMutex());`, or null when the BLAS needs none. OpenBLAS's
// serial build shares its work buffers between callers without a lock: two threads multiplying
// at once get wrong products (measured: about 4% of 64 x 64 products from two threads with its
// Haswell kernels). Its pthread build, which DCS installs, locks them itself, and so do its
// OpenMP build and other BLAS libraries; with those this returns null and runs updating at once
// on several threads multiply in parallel. Not OpenBLAS: locked, since whether it shares
// buffers is unknown.
absl::Mutex* BlasMutex();

// The OpenBLAS core in use ("Haswell", "SkylakeX", ...), or empty if libtorch's BLAS is not
// OpenBLAS.
std::string BlasCoreName();

// The instruction set ATen dispatches its operators for, named as ATEN_CPU_CAPABILITY names
// it: "default" (no AVX), "avx2" or "avx512"; empty if libtorch does not report it. Fixes
// the choice for the rest of the process if no operator has run yet.
std::string AtenCpuCapability();

// The numeric libraries and the kernels this process computes with, in one line (results are
// bit-for-bit reproducible only under the same fingerprint):
// "libtorch 1.13.0, openblas Haswell, aten avx2". libtorch's version is the one compiled
// against; "openblas unknown" if the BLAS is not OpenBLAS.
std::string NumericFingerprint();

// libtorch, as compiled against, and the kernels its operators run on: the OpenBLAS core, the
// ATen instruction set (the parts of NumericFingerprint, for worker registration).
std::vector<LibraryVersion> LibraryVersions();

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TORCH_RUNTIME_H_
