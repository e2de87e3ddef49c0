// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_TABLE_H_
#define DCS_COORDINATOR_RUN_TABLE_H_

// The store's runs and their leases (coordinator/store.h holds the whole store).
//
// Leases (docs/architecture.md §9). Each run has one learner lease (slot kLearnerSlot) and one
// lease per env slot. A lease is free or held by a worker until a deadline; the holder renews it
// before the deadline; a lapsed lease goes back to the queue (Store::ExpireLeases, which every
// Acquire runs first). Each grant raises the lease's epoch, and every call a holder makes names the
// epoch it was granted, so a worker that comes back after its lease moved is refused
// (FAILED_PRECONDITION), never counted twice. When a run's learner lease is granted anew, its slot
// leases are freed: they pointed at the old learner.
//
// Numeric libraries (docs/architecture.md §8): a run remembers the numeric fingerprint of the first
// learner that took it and of the first actor that stepped one of its slots; only workers
// with the same fingerprint as their role's get its leases.
//
// Thread-safe: every call is one transaction on the store's one connection; it returns after
// the transaction committed. Times are passed in (tests drive the clock).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "absl/types/span.h"
#include "coordinator/run_state.h"
#include "run/lease_key.h"
#include "run/worker_reports.h"

namespace dcs::coordinator {

namespace internal {
class StoreConnection;
}  // namespace internal

// Leases and what learners report of runs, in the words the workers use too.
using run::kLearnerSlot;
using run::LeaseKey;
using run::RunProgress;

// A run as submitted.
struct RunSubmission {
  std::string request_id;  // client-chosen; a repeated id returns the run it created
  std::string config;      // the run config (YAML), with the seed applied
  uint64_t seed = 0;
  std::string env;
  int n_envs = 1;
  int64_t total_timesteps = 0;
};

struct RunRecord {
  std::string id;  // "run-<n>"
  RunSubmission submission;
  RunState state = RunState::kQueued;
  std::string error;     // why it failed or was cancelled
  std::string learner_numerics;  // the numeric fingerprint of its learners
  std::string actor_numerics;    // of its actors
  RunProgress progress;  // as its learners last reported, timesteps the furthest of them
  std::string checkpoint;  // the latest checkpoint's name; empty before the first
  absl::Time created_at;
  absl::Time updated_at;
  std::string sweep_id;      // the sweep it belongs to ("sweep-<n>"); empty for a run alone
  std::optional<int> trial;  // its trial's index in that sweep
};

// A run leased to a learner.
struct LearnerLease {
  LeaseKey key;
  RunRecord run;
  // Its trial's condition and observation mode (TrialRecord), empty for a run alone: what the
  // learner labels the run's metrics with.
  std::string condition;
  std::string observe;
};

// An env slot leased to an actor, with where the run's learner listens.
struct SlotLease {
  LeaseKey key;
  std::string learner_address;
  int64_t learner_epoch = 0;
  uint64_t seed = 0;
  std::string config;
};

class RunTable {
 public:
  RunTable(const RunTable&) = delete;
  RunTable& operator=(const RunTable&) = delete;

  // Queues a run (or returns the one `submission.request_id` already created).
  // INVALID_ARGUMENT for an empty request id or config, or n_envs < 1.
  absl::StatusOr<RunRecord> SubmitRun(const RunSubmission& submission, absl::Time now);

  // NOT_FOUND for an unknown id.
  absl::StatusOr<RunRecord> GetRun(absl::string_view run_id);
  // Every run, oldest first.
  absl::StatusOr<std::vector<RunRecord>> ListRuns();

  // Cancels a queued or running run and frees its leases. NOT_FOUND, or FAILED_PRECONDITION if
  // it already ended.
  absl::StatusOr<RunRecord> CancelRun(absl::string_view run_id, absl::Time now);

  // Removes runs for good, every one of `run_ids` or, on an error, none, with every row the
  // store holds of them (leases, checkpoints' index, evaluations and their results); returns
  // them as they were, in `run_ids`' order, each once. Their ids are never given again. Their
  // directories are the caller's to remove once this returns (coordinator/run_removal.h).
  // INVALID_ARGUMENT for no id; NOT_FOUND for an unknown one; FAILED_PRECONDITION (naming it)
  // for a run CheckRemovable refuses (queued, running, a grid evaluation open) or one of a
  // sweep: a sweep's runs go with it (SweepTable::DeleteSweeps), as its report needs them all.
  absl::StatusOr<std::vector<RunRecord>> DeleteRuns(absl::Span<const std::string> run_ids);
  // Those of `names` that are the ids of removed runs: ids this store gave that no run has now.
  // What is left of a removal that ended before its directories went (coordinator/run_removal.h).
  absl::StatusOr<std::vector<std::string>> RemovedRuns(absl::Span<const std::string> names);

  // A queued run a learner with `numerics` may take, leased to `holder` (listening at
  // `address`) until now + lease_duration; the run becomes running. Fair across sweeps: the
  // run whose sweep has the fewest running runs (a run alone counts as a sweep of its own),
  // the oldest among those; so a small sweep submitted after a big one is not starved.
  // nullopt if there is none; FAILED_PRECONDITION, naming both fingerprints, if the only queued
  // runs compute with other numerics.
  absl::StatusOr<std::optional<LearnerLease>> AcquireRun(absl::string_view holder,
                                                         absl::string_view address,
                                                         absl::string_view numerics,
                                                         absl::Time now);

  // A free env slot of a running run (whose learner holds its lease) that an actor with
  // `numerics` may step, skipping the runs whose learner lease is, at the same epoch, among
  // `complete_learners` (learners that told the actor they have all their steps: their runs
  // need no slots while they evaluate; the run's next learner, after one dies, does). nullopt
  // if there is none; FAILED_PRECONDITION as AcquireRun when the runs waiting for actors
  // compute with others.
  absl::StatusOr<std::optional<SlotLease>> AcquireSlot(absl::string_view holder,
                                                       absl::string_view numerics,
                                                       absl::Span<const LeaseKey> complete_learners,
                                                       absl::Time now);

  // Extends a held lease to now + lease_duration. FAILED_PRECONDITION if the lease moved (its
  // epoch is newer), lapsed and went back to the queue, or its run ended (the message says
  // which); NOT_FOUND for an unknown run or slot. Not synced (store.h): a reopened store gives
  // every held lease a full duration.
  absl::Status RenewLease(const LeaseKey& key, absl::Time now);

  // The holder gives a lease back (it stops stepping the slot, say). Errors as RenewLease. Not
  // synced: a release the machine's crash loses lapses instead.
  absl::Status ReleaseLease(const LeaseKey& key, absl::Time now);

  // The learner holding `key` (a learner lease) reports progress. The run's timesteps never go
  // down: they are the furthest step any of its learners reported, so a learner that resumed
  // from a checkpoint older than its predecessor's last report leaves them until it passes
  // them (a handover repeats steps, it does not undo progress). Errors as RenewLease. Not
  // synced: the learner reports again.
  absl::Status ReportProgress(const LeaseKey& key, const RunProgress& progress, absl::Time now);

  // The learner holding `key` ends its run: completed, or failed with `error`; every lease of
  // the run is freed. Errors as RenewLease; INVALID_ARGUMENT for another state.
  absl::Status FinishRun(const LeaseKey& key, RunState state, absl::string_view error,
                         absl::Time now);

 private:
  friend class Store;
  explicit RunTable(internal::StoreConnection& connection) : connection_(connection) {}

  internal::StoreConnection& connection_;  // the Store's, which owns this table too
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_TABLE_H_
