// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_LEASE_REAPER_H_
#define DCS_COORDINATOR_LEASE_REAPER_H_

// Returns lapsed leases to the queue as they lapse, rather than at the next Acquire (which
// expires them too), so that queue depths and run states do not wait for a worker to ask; and
// counts every lapse, those an Acquire found first included (under load the workers' Acquire
// calls find nearly all of them). Driven by its caller's clock: the coordinator ticks it about
// once a second, a test at the times it chooses. Thread-compatible: one caller ticks it. Borrows
// the store, which must outlive it.

#include <cstdint>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "coordinator/store.h"

namespace dcs::coordinator {

class LeaseReaper {
 public:
  // Counts lapses from those the store has counted when it is made.
  explicit LeaseReaper(Store& store);

  LeaseReaper(const LeaseReaper&) = delete;
  LeaseReaper& operator=(const LeaseReaper&) = delete;

  struct Reaped {
    // The store's error returning the leases lapsed at `now` to the queue, if it failed: the
    // next tick tries again.
    absl::Status status;
    // Leases that lapsed since the last tick, whoever returned them.
    int64_t lapsed = 0;
  };
  // Returns the leases lapsed at `now` to the queue (Store::ExpireLeases).
  Reaped Tick(absl::Time now);

 private:
  Store& store_;
  int64_t counted_;  // the store's count of lapses at the last tick
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_LEASE_REAPER_H_
