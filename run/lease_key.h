// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_LEASE_KEY_H_
#define DCS_RUN_LEASE_KEY_H_

// The name of a lease on a run, as the coordinator grants it and its holder (a learner for the
// run, an actor for one of its env slots) names it in every call it makes under it. Plain data.

#include <cstdint>
#include <string>

namespace dcs::run {

// The slot number of a run's learner lease.
inline constexpr int kLearnerSlot = -1;

// Names a lease as its holder was granted it.
struct LeaseKey {
  std::string run_id;
  int slot = kLearnerSlot;
  int64_t epoch = 0;
};

}  // namespace dcs::run

#endif  // DCS_RUN_LEASE_KEY_H_
