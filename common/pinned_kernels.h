// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_PINNED_KERNELS_H_
#define DCS_COMMON_PINNED_KERNELS_H_

// The numeric kernels every DCS process that trains or updates pins (docs/architecture.md §8), and
// the environment that starts such a program with them. Free of libtorch, so that what starts a
// trainer (the `dcs` client, `dcs up`, the tests) can set them and `dcs version` can show them;
// learner/torch_runtime.h applies them inside the trainer. Thread-safe (constants and a pure
// function).

#include <string>
#include <vector>

namespace dcs {

// An environment variable a numeric library reads when the process starts, and the value DCS
// pins it to.
struct KernelVariable {
  const char* name;
  const char* value;
};

// The pinned kernels. OpenBLAS and ATen (libtorch's operators) each pick their kernels from
// the CPU they run on (OpenBLAS by CPU model, ATen by instruction set), and kernels for other
// CPUs add in other orders, so two machines would give two runs from one seed. DCS fixes both
// to their AVX2 and FMA kernels, the best that every such x86-64 CPU runs:
// OpenBLAS's "Haswell" core (whose blocking sizes are constants, not read from the cache
// sizes) and ATen's "avx2" dispatch. Both are read once, when the library loads or first
// dispatches, so only a process started with them set has them: whatever starts a trainer
// sets them (PinnedKernelEnvironment), and a trainer started without them runs itself again
// with them (learner::PinNumericKernels), paying libtorch's start-up twice.
// OpenBLAS's pthread build also splits a product between threads, which changes its sums, so it
// is pinned to the caller's thread (docs/architecture.md §8: one thread per run).
// The deployments (docker-compose.yml, deploy/kubernetes) set them for the learner too, and
// tests/deploy/pinned_kernels.py reads this table to check them: keep one {"NAME", "value"} a
// line.
inline constexpr KernelVariable kPinnedKernels[] = {
    {"OPENBLAS_CORETYPE", "Haswell"},
    {"OPENBLAS_NUM_THREADS", "1"},
    {"ATEN_CPU_CAPABILITY", "avx2"},
};

// `environment` ("NAME=value" entries up to a null pointer, as `environ` holds them) with every
// variable of kPinnedKernels set to its pinned value: an entry of that name is replaced where
// it stands (a second entry of that name is dropped), a missing one appended in the table's
// order; every other entry is kept, in order.
// For execve: the program it starts computes with the pinned kernels from its first
// instruction.
std::vector<std::string> PinnedKernelEnvironment(const char* const* environment);

}  // namespace dcs

#endif  // DCS_COMMON_PINNED_KERNELS_H_
