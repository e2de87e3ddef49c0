// Copyright 2026 The DCS Authors.
#include "services/signals.h"

#include <pthread.h>

#include <algorithm>
#include <cerrno>
#include <ctime>

#include "absl/time/clock.h"

namespace dcs::services {

BlockedSignals::BlockedSignals(std::initializer_list<int> signals) {
  sigemptyset(&signals_);
  for (int signal : signals) sigaddset(&signals_, signal);
  pthread_sigmask(SIG_BLOCK, &signals_, &original_mask_);
}

BlockedSignals::~BlockedSignals() { pthread_sigmask(SIG_SETMASK, &original_mask_, nullptr); }

int BlockedSignals::Wait(absl::Duration timeout) const {
  if (timeout == absl::InfiniteDuration()) {
    int signal = 0;
    while (sigwait(&signals_, &signal) != 0) {
    }
    return signal;
  }
  const absl::Time deadline = absl::Now() + timeout;
  while (true) {
    const timespec limit =
        absl::ToTimespec(std::max(deadline - absl::Now(), absl::ZeroDuration()));
    const int signal = sigtimedwait(&signals_, nullptr, &limit);
    if (signal > 0) return signal;
    if (errno == EAGAIN) return 0;  // timed out; EINTR: wait for the rest
  }
}

}  // namespace dcs::services
