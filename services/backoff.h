// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_BACKOFF_H_
#define DCS_SERVICES_BACKOFF_H_

// Exponential backoff with jitter for retrying a peer that is down, so that many workers do
// not reconnect to a restarted coordinator in step. Thread-safe (pure function).

#include "absl/random/bit_gen_ref.h"
#include "absl/time/time.h"

namespace dcs::services {

struct BackoffPolicy {
  absl::Duration initial = absl::Milliseconds(250);
  double multiplier = 2.0;
  absl::Duration max = absl::Seconds(8);
  double jitter = 0.2;  // the delay is scaled by a uniform factor in [1 - jitter, 1 + jitter]
};

// The delay before retry number `attempt` (1 for the first retry):
// min(max, initial * multiplier^(attempt - 1)), jittered. REQUIRES: attempt >= 1.
absl::Duration BackoffDelay(const BackoffPolicy& policy, int attempt, absl::BitGenRef random);

}  // namespace dcs::services

#endif  // DCS_SERVICES_BACKOFF_H_
