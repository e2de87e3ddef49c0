// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TORCH_RUNTIME_H_
#define DCS_LEARNER_TORCH_RUNTIME_H_

// Process-wide libtorch settings. Not thread-safe: call from main before any torch work.
//
// DESIGN.md §4: with libtorch pinned to one thread per run, the same sweep gives the same
// report bit for bit however many learners share a machine; a learner process runs one run.

#include <vector>

#include "absl/status/status.h"
#include "common/library_version.h"

namespace dcs::learner {

// Sets libtorch's intra-op and inter-op thread pools to `threads` each.
// Returns INVALID_ARGUMENT if `threads` < 1, and FAILED_PRECONDITION if libtorch has already
// started its inter-op pool (it can be sized only once per process).
absl::Status PinTorchThreads(int threads);

// libtorch, as compiled against.
std::vector<LibraryVersion> LibraryVersions();

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TORCH_RUNTIME_H_
