// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEASE_RENEWALS_H_
#define DCS_SERVICES_LEASE_RENEWALS_H_

// A worker's lease renewals (docs/architecture.md §9): the leases that fall due, renewed at once,
// each by its own call. On a loaded machine a call waits for the scheduler far longer than for the
// coordinator, and one call after another for 16 runs took longer than a lease lasts
// (bench/RESULTS.md, issue 14's load). A learner renews its runs' leases and an actor its slots'
// from the manager thread that takes them, never from a thread that works under them: a piece of
// work longer than a third of a lease would let it lapse. Thread-safe (gRPC stubs are).

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "absl/types/span.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "run/lease_key.h"
#include "services/log.h"
#include "services/unary_call.h"

namespace dcs::services {

// Renews every lease in `leases` with a call of its own, each with `timeout`, and waits for
// all of them. Returns, in the order of `leases`, how long the coordinator extended each one
// for, or why not: IsLeaseLost when it is no longer the caller's, IsTransient when it is worth
// renewing again.
std::vector<absl::StatusOr<absl::Duration>> RenewLeases(v1::CoordinatorService::Stub& coordinator,
                                                        absl::Span<const run::LeaseKey> leases,
                                                        absl::Duration timeout);

// Renews the leases of `items` that fall due: a map, guarded by `mu`, of shared pointers to
// items with `lease` (a run::LeaseKey), `renewed_at` (an absl::Time only the caller's
// thread touches), and the atomic flags `lost` and `done` (services/finished_threads.h). Due is
// a third of `lease_duration` (guarded by `mu`) after the last renewal; a lease renewed counts
// from before the calls, and `lease_duration` becomes what the coordinator says. Calls
// `lose(item)` once for an item whose lease is no longer its holder's; a transient failure is
// logged and tried again at the next call.
template <typename Map, typename Lose>
void RenewDueLeases(v1::CoordinatorService::Stub& coordinator, absl::Duration timeout,
                    absl::Mutex& mu, Map& items, absl::Duration& lease_duration, Lose lose) {
  std::vector<typename Map::mapped_type> due;
  std::vector<run::LeaseKey> leases;
  {
    absl::MutexLock lock(&mu);
    const absl::Duration period = lease_duration / 3;
    for (const auto& [key, item] : items) {
      if (item->lost || item->done || absl::Now() - item->renewed_at < period) continue;
      due.push_back(item);
      leases.push_back(item->lease);
    }
  }
  const absl::Time sent = absl::Now();
  const std::vector<absl::StatusOr<absl::Duration>> renewed =
      RenewLeases(coordinator, leases, timeout);
  for (size_t i = 0; i < due.size(); ++i) {
    auto& item = *due[i];
    if (renewed[i].ok()) {
      item.renewed_at = sent;
      absl::MutexLock lock(&mu);
      lease_duration = *renewed[i];
      continue;
    }
    const bool lost = IsLeaseLost(renewed[i].status());
    Log(LogLevel::kWarning, lost ? "lost a lease" : "cannot renew a lease yet",
        {{"run_id", item.lease.run_id},
         {"slot",
          item.lease.slot == run::kLearnerSlot ? "learner" : std::to_string(item.lease.slot)},
         {"error", renewed[i].status().ToString()}});
    if (lost) lose(item);
  }
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEASE_RENEWALS_H_
