// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_EIGEN_BLOCKING_H_
#define DCS_ACTOR_EIGEN_BLOCKING_H_

// Eigen's matrix-matrix products cut the depth of a long product into blocks sized from the
// cache sizes Eigen reads from the CPU, and a product cut into other blocks sums in another
// order: the same binary would give other bits on a CPU with other caches. PinEigenBlocking
// replaces the sizes read from the CPU by constants, for the whole process, so that a product
// gives the same bits on every x86-64-v3 CPU, Intel or AMD (docs/architecture.md §8). Every DCS
// function that multiplies matrices by matrices with Eigen calls it first (the learner's passes,
// learner/actor_critic.cc); matrix-vector products (actors' inference) block by constants of their
// own. The instruction set, the other choice that shapes Eigen's kernels, is fixed when DCS is
// compiled (x86-64-v3: CMakeLists.txt); Eigen runs on the caller's thread only.
//
// Thread-safe: the first call pins, on whichever thread; later calls only check that it did.

namespace dcs::actor {

// The cache sizes Eigen blocks its products for, in bytes: a common core's (32 KiB of L1 data,
// 1 MiB of L2) and a share of L3. They only shape how fast a long product runs.
inline constexpr int kEigenL1Bytes = 32 * 1024;
inline constexpr int kEigenL2Bytes = 1024 * 1024;
inline constexpr int kEigenL3Bytes = 8 * 1024 * 1024;

void PinEigenBlocking();

}  // namespace dcs::actor

#endif  // DCS_ACTOR_EIGEN_BLOCKING_H_
