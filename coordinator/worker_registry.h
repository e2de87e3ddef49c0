// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_WORKER_REGISTRY_H_
#define DCS_COORDINATOR_WORKER_REGISTRY_H_

// The coordinator's view of its workers: who registered, their role and address, and whether
// their heartbeats still arrive. Thread-safe. Callers pass the current time, so tests drive a
// fake clock.
//
// Life of a worker: Register -> ALIVE; a heartbeat older than `lost_after` -> LOST (a later
// heartbeat makes it ALIVE again); silent for `forget_after` -> forgotten; Unregister (a clean
// shutdown) -> forgotten at once. A worker the registry does not know (the coordinator
// restarted, or forgot it) gets NOT_FOUND on Heartbeat and registers again.

#include <cstdint>
#include <memory>
#include <string>
#include "absl/strings/string_view.h"
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_map.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "common/worker_info.h"

namespace dcs::coordinator {

enum class WorkerState { kAlive, kLost };

// "alive" or "lost".
absl::string_view WorkerStateName(WorkerState state);

struct WorkerRecord {
  std::string id;  // assigned by the registry: "<role>-<n>"
  WorkerInfo info;
  WorkerState state = WorkerState::kAlive;
  absl::Time registered_at;
  absl::Time last_heartbeat_at;
};

struct WorkerRegistryOptions {
  absl::Duration heartbeat_interval = absl::Seconds(1);  // what workers are told to use
  absl::Duration lost_after = absl::Seconds(5);          // silence before a worker is LOST
  absl::Duration forget_after = absl::Minutes(10);       // silence before it is forgotten
};

class WorkerRegistry {
 public:
  // Returns INVALID_ARGUMENT unless 0 < heartbeat_interval, 2 * heartbeat_interval <=
  // lost_after (one lost heartbeat must not mark a worker LOST) and lost_after < forget_after.
  static absl::StatusOr<std::unique_ptr<WorkerRegistry>> Create(WorkerRegistryOptions options);

  WorkerRegistry(const WorkerRegistry&) = delete;
  WorkerRegistry& operator=(const WorkerRegistry&) = delete;

  // Adds a worker and returns its new id. INVALID_ARGUMENT if `info.address` is empty.
  absl::StatusOr<std::string> Register(WorkerInfo info, absl::Time now);

  // Records a heartbeat. NOT_FOUND if `id` is unknown or was forgotten.
  absl::Status Heartbeat(absl::string_view id, absl::Time now);

  // Forgets a worker that is shutting down. NOT_FOUND if `id` is unknown or was forgotten.
  absl::Status Unregister(absl::string_view id, absl::Time now);

  // Every known worker with its state as of `now`: learners first, each role in registration
  // order.
  std::vector<WorkerRecord> List(absl::Time now) const;

  const WorkerRegistryOptions& options() const { return options_; }

 private:
  explicit WorkerRegistry(WorkerRegistryOptions options) : options_(options) {}

  // Drops workers silent for `forget_after`.
  void ForgetSilentLocked(absl::Time now) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);

  // Fixed at construction.
  const WorkerRegistryOptions options_;

  struct Entry {
    int64_t sequence;  // registration order, for listing
    WorkerRecord record;
  };

  mutable absl::Mutex mu_;
  absl::flat_hash_map<std::string, Entry> workers_ ABSL_GUARDED_BY(mu_);
  int64_t next_sequence_ ABSL_GUARDED_BY(mu_) = 1;
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_WORKER_REGISTRY_H_
