// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_EVENTUALLY_H_
#define DCS_TESTS_TESTING_EVENTUALLY_H_

// Waiting in tests for something another thread or process does. Thread-compatible.

#include "absl/functional/function_ref.h"
#include "absl/time/time.h"

namespace dcs::testing {

// Polls `condition` every `poll` until it holds (true) or `timeout` has passed (stretched in a
// sanitized build: tests/testing/slowdown.h); then asks once more, so a condition that became
// true at the deadline is not missed.
bool Eventually(absl::FunctionRef<bool()> condition, absl::Duration timeout = absl::Seconds(20),
                absl::Duration poll = absl::Milliseconds(10));

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_EVENTUALLY_H_
