// Copyright 2026 The DCS Authors.
#include "tests/testing/eventually.h"

#include "absl/time/clock.h"
#include "tests/testing/slowdown.h"

namespace dcs::testing {

bool Eventually(absl::FunctionRef<bool()> condition, absl::Duration timeout,
                absl::Duration poll) {
  const absl::Time deadline = absl::Now() + Patient(timeout);
  while (absl::Now() < deadline) {
    if (condition()) return true;
    absl::SleepFor(poll);
  }
  return condition();
}

}  // namespace dcs::testing
