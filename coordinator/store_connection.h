// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STORE_CONNECTION_H_
#define DCS_COORDINATOR_STORE_CONNECTION_H_

// The one SQLite connection every table of the store (coordinator/store.h) works on, behind
// one mutex, and the one way a call touches it: a transaction that commits if the call
// succeeds, rolls back otherwise, and turns SQLite's errors into statuses naming the file.
// Internal to the store: only its own .cc files include this header.
//
// Thread-safe: one call's transaction at a time; a body runs with the mutex held and must not
// call Transaction again.

#include <SQLiteCpp/Database.h>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"

namespace dcs::coordinator::internal {

// An SQLite error on the store at `path` as a status naming the file: UNAVAILABLE for a full
// disk (SQLITE_FULL) or a locked file, since nothing was stored and the same call may succeed
// later (status.h: "the client may retry just this call"); DATA_LOSS for a corrupt file or one
// that is not a database; else INTERNAL.
absl::Status StoreError(const std::string& path, const SQLite::Exception& error);

// How a transaction's commit reaches the disk (SQLite's `synchronous`, WAL mode).
enum class Commit {
  // Synced before the call returns (FULL): what it wrote survives a crash of the machine.
  kSynced,
  // Written to the WAL, not waited for (NORMAL): it survives the coordinator's crash, and a
  // crash of the machine may lose it, with the other unsynced commits since the last synced
  // one, but never one before (the WAL replays a prefix of the commits) and never one a synced
  // commit followed. For what the cluster redoes on its own when it is lost: a lease's renewal
  // (a reopened store gives every held lease a full duration anyway), a release (the lease
  // lapses), a learner's progress (it reports again), evaluation jobs' results (their leases
  // lapse, and the jobs run again to the same returns). Never for what hands out a lease whose
  // epoch fences out a former holder (a run's, a slot's): that holds only if the store never
  // grants the same epoch twice.
  kUnsynced,
};

class StoreConnection {
 public:
  // Takes over `db`, opened and migrated. Leases granted from now on last `lease_duration`.
  StoreConnection(std::unique_ptr<SQLite::Database> db, absl::Duration lease_duration);

  StoreConnection(const StoreConnection&) = delete;
  StoreConnection& operator=(const StoreConnection&) = delete;

  absl::Duration lease_duration() const { return lease_duration_; }

  // Runs `body(db)` in one BEGIN IMMEDIATE transaction and returns what it returns (a Status
  // or a StatusOr), committing as `commit` says if that is OK and rolling back otherwise.
  // SQLite's errors (thrown by SQLiteCpp) roll back too and become StoreError.
  template <typename Body>
  auto Transaction(Body body, Commit commit = Commit::kSynced)
      -> decltype(body(std::declval<SQLite::Database&>()));

  // Runs `body(db)` with the mutex held and no transaction open (SQLite's online backup opens
  // its own), so that no call's transaction interleaves with it.
  template <typename Body>
  auto Locked(Body body) -> decltype(body(std::declval<SQLite::Database&>()));

  // Frees the leases of every kind lapsed at `now` (store_rows::ExpireLapsed) and returns how
  // many; LeasesLapsed counts them once the transaction commits. Inside a Transaction's body
  // only, on the `db` it was given.
  absl::StatusOr<int> ExpireLapsedLeases(SQLite::Database& db, absl::Time now)
      ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);

  // How many leases have lapsed since the store was opened, whichever call expired them.
  int64_t LeasesLapsed();

 private:
  absl::Mutex mu_;
  const std::unique_ptr<SQLite::Database> db_ ABSL_GUARDED_BY(mu_);
  const absl::Duration lease_duration_;
  int64_t leases_lapsed_ ABSL_GUARDED_BY(mu_) = 0;
  int64_t leases_lapsing_ ABSL_GUARDED_BY(mu_) = 0;  // by the open transaction
  Commit synchronous_ ABSL_GUARDED_BY(mu_) = Commit::kSynced;  // the connection's setting
};

// Rolls back the open transaction of `db`, if one is still open: after some errors (a full disk
// among them) SQLite has rolled it back already, and a ROLLBACK would fail and hide the first
// error. Never throws.
void RollBackIfActive(SQLite::Database& db) noexcept;

template <typename Body>
auto StoreConnection::Transaction(Body body, Commit commit)
    -> decltype(body(std::declval<SQLite::Database&>())) {
  absl::MutexLock lock(&mu_);
  leases_lapsing_ = 0;
  try {
    if (commit != synchronous_) {  // set between transactions: SQLite reads it at the commit
      db_->exec(commit == Commit::kSynced ? "PRAGMA synchronous = FULL"
                                          : "PRAGMA synchronous = NORMAL");
      synchronous_ = commit;
    }
    db_->exec("BEGIN IMMEDIATE");
    try {
      auto result = body(*db_);
      db_->exec(result.ok() ? "COMMIT" : "ROLLBACK");
      if (result.ok()) leases_lapsed_ += leases_lapsing_;
      return result;
    } catch (...) {
      RollBackIfActive(*db_);
      throw;
    }
  } catch (const SQLite::Exception& e) {
    return StoreError(db_->getFilename(), e);
  }
}

template <typename Body>
auto StoreConnection::Locked(Body body) -> decltype(body(std::declval<SQLite::Database&>())) {
  absl::MutexLock lock(&mu_);
  return body(*db_);
}

}  // namespace dcs::coordinator::internal

#endif  // DCS_COORDINATOR_STORE_CONNECTION_H_
