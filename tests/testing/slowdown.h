// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_SLOWDOWN_H_
#define DCS_TESTS_TESTING_SLOWDOWN_H_

// How long a test waits, in the build it runs in. A sanitized build (scripts/sanitize) runs the
// same code several times slower; its tests must fail on what is wrong, not on what is slow, so
// every deadline a test sets for the code under test (a process to finish, a sweep to complete,
// a condition to hold) goes through Patient. What a test asserts about speed is measured in
// bench/, never here. gRPC's tests stretch their deadlines the same way; these factors are
// what the first sanitized runs of DCS's tests needed on two cores, with room to spare.

#include "absl/time/time.h"

namespace dcs::testing {

#if defined(__SANITIZE_THREAD__)
inline constexpr int kSlowdown = 10;
#elif defined(__SANITIZE_ADDRESS__)
inline constexpr int kSlowdown = 4;
#else
inline constexpr int kSlowdown = 1;
#endif

// `deadline`, stretched by this build's slowdown.
inline absl::Duration Patient(absl::Duration deadline) { return deadline * kSlowdown; }

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_SLOWDOWN_H_
