// Copyright 2026 The DCS Authors.
#include "services/backoff.h"

#include <algorithm>
#include <cmath>

#include "absl/random/distributions.h"

namespace dcs::services {

absl::Duration BackoffDelay(const BackoffPolicy& policy, int attempt, absl::BitGenRef random) {
  // Duration arithmetic saturates at infinity, so a large attempt still yields `max`.
  const double growth = std::pow(policy.multiplier, std::min(attempt - 1, 64));
  const absl::Duration base = std::min(policy.max, policy.initial * growth);
  return base * absl::Uniform(random, 1.0 - policy.jitter, 1.0 + policy.jitter);
}

}  // namespace dcs::services
