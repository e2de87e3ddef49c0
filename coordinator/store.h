// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STORE_H_
#define DCS_COORDINATOR_STORE_H_

// The coordinator's durable state in one SQLite file (WAL, schema versioned
// by PRAGMA user_version with forward-only migrations: coordinator/store_schema.h). A Store
// owns the file's one connection and hands out a table per concern, all over that connection:
//
//   runs()         runs and their leases (coordinator/run_table.h)
//   sweeps()       sweeps, their trials and runs (coordinator/sweep_table.h)
//   studies()      ask-and-tell studies (coordinator/study_table.h)
//   evaluations()  evaluations as jobs for actors, and their results
//                  (coordinator/evaluation_table.h)
//   checkpoints()  the index of runs' checkpoints (coordinator/checkpoint_table.h)
//
// and itself does what spans them: lapsed leases of every kind, counts for metrics
// (coordinator/store_counts.h), backups.
// Every call is one transaction and returns after it committed, so whatever a caller
// acknowledges on the strength of a call survives the coordinator's crash, and the machine's:
// a commit is synced to the disk before the call returns. The frequent calls of workers are
// not synced (their tables say which), since the cluster redoes them if a crash of the machine
// loses them: a lease's renewal and release, a learner's progress, evaluation jobs' grants and
// results.
// They cost no wait for the disk, and a crash loses them only with the unsynced calls after
// them (internal::Commit, coordinator/store_connection.h).
//
// Thread-safe: the connection is behind one mutex, and each call holds it for its transaction.
// The tables belong to the Store and live as long as it does.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "coordinator/checkpoint_table.h"
#include "coordinator/evaluation_table.h"
#include "coordinator/run_state.h"
#include "coordinator/run_table.h"
#include "coordinator/store_counts.h"
#include "coordinator/study_table.h"
#include "coordinator/sweep_table.h"

namespace dcs::coordinator {

struct StoreOptions {
  absl::Duration lease_duration = absl::Seconds(10);
};

// What a backup of the store holds (Store::Backup).
struct BackupCounts {
  int64_t runs = 0;
  int64_t sweeps = 0;
  int64_t studies = 0;
};

class Store {
 public:
  // Opens (creating) the database at `path` and migrates it to the current schema.
  // Leases held when the previous coordinator stopped get a full lease_duration from `now`, so
  // their holders can renew before anything moves. FAILED_PRECONDITION for a database written by
  // a newer DCS (its schema version is unknown); INTERNAL naming the file for SQLite errors.
  static absl::StatusOr<std::unique_ptr<Store>> Open(const std::string& path,
                                                     StoreOptions options, absl::Time now);
  ~Store();

  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  RunTable& runs() { return runs_; }
  SweepTable& sweeps() { return sweeps_; }
  StudyTable& studies() { return studies_; }
  EvaluationTable& evaluations() { return evaluations_; }
  CheckpointTable& checkpoints() { return checkpoints_; }

  // Frees every lease whose deadline passed; a run whose learner lease lapsed goes back to
  // queued (and its slot leases are freed); a lapsed evaluation job goes back to the queue.
  // Returns how many leases lapsed.
  absl::StatusOr<int> ExpireLeases(absl::Time now);
  // How many leases have lapsed since the store was opened, whichever call expired them
  // (ExpireLeases or an Acquire): counted once each, when the expiring transaction commits.
  int64_t LeasesLapsed();

  // What metrics show of the store (coordinator/store_counts.h), in one transaction.
  absl::StatusOr<StoreCounts> Counts();

  // Writes a consistent copy of the store as of one moment (SQLite's online backup) to `path`,
  // atomically: into a temporary file beside it, synced, then renamed over it; a failed backup
  // leaves nothing behind. Open opens the copy as it would this store, and a coordinator on it
  // goes on as one restarted on this store would (given the runs' files, which are not in the
  // store: coordinator/run_files.h). The copy is taken in one step under the store's lock, so
  // every other call waits for it (bench/RESULTS.md, Reliability: how long). Returns what the
  // copy holds. Errors name `path`: PERMISSION_DENIED for a directory it may not write in,
  // NOT_FOUND for a missing one, RESOURCE_EXHAUSTED for a full disk, else INTERNAL.
  absl::StatusOr<BackupCounts> Backup(const std::string& path);

 private:
  explicit Store(std::unique_ptr<internal::StoreConnection> connection);

  const std::unique_ptr<internal::StoreConnection> connection_;
  RunTable runs_;
  SweepTable sweeps_;
  StudyTable studies_;
  EvaluationTable evaluations_;
  CheckpointTable checkpoints_;
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STORE_H_
