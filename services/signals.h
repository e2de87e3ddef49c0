// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_SIGNALS_H_
#define DCS_SERVICES_SIGNALS_H_

// Signals handled synchronously by the main thread, as a scoped object: the constructor
// blocks the signals (every thread started afterwards inherits the mask, so none of them is
// interrupted), Wait() receives them, and the destructor restores delivery, so that a second
// Ctrl-C during a slow shutdown ends the process at once.
//
// Confined to the main thread. REQUIRES: constructed in main before any thread starts.

#include <signal.h>

#include <initializer_list>

#include "absl/time/time.h"

namespace dcs::services {

class BlockedSignals {
 public:
  explicit BlockedSignals(std::initializer_list<int> signals);
  ~BlockedSignals();
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;

  // Returns the next pending signal of the set, or 0 if none arrives within `timeout`.
  int Wait(absl::Duration timeout = absl::InfiniteDuration()) const;

  // The signal mask the process had before construction: what a child process should start
  // with.
  const sigset_t& original_mask() const { return original_mask_; }

 private:
  sigset_t signals_;
  sigset_t original_mask_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_SIGNALS_H_
