// Copyright 2026 The DCS Authors.
#include "coordinator/store.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>
#include <fcntl.h>
#include <sqlite3.h>
#include <unistd.h>

#include <utility>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"
#include "coordinator/store_schema.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

// The error of SQLite call `rc` of connection `db` writing the backup `path`: by the system's
// errno where there is one (a directory it may not write in, a full disk), else SQLite's.
absl::Status BackupError(sqlite3* db, int rc, const std::string& path) {
  if (rc == SQLITE_FULL) return FileError(ENOSPC, "cannot back the store up to", path);
  const int error = db == nullptr ? 0 : sqlite3_system_errno(db);
  if (error != 0) return FileError(error, "cannot back the store up to", path);
  return absl::InternalError(absl::StrCat("cannot back the store up to ", path, ": ",
                                          db == nullptr ? sqlite3_errstr(rc) : sqlite3_errmsg(db)));
}

struct CloseConnection {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};

}  // namespace

Store::Store(std::unique_ptr<internal::StoreConnection> connection)
    : connection_(std::move(connection)),
      runs_(*connection_),
      sweeps_(*connection_),
      studies_(*connection_),
      evaluations_(*connection_),
      checkpoints_(*connection_) {}

Store::~Store() = default;

absl::StatusOr<std::unique_ptr<Store>> Store::Open(const std::string& path, StoreOptions options,
                                                   absl::Time now) {
  try {
    auto db = std::make_unique<SQLite::Database>(
        path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE | SQLite::OPEN_FULLMUTEX);
    db->setBusyTimeout(5000);
    db->exec("PRAGMA journal_mode = WAL");
    db->exec("PRAGMA synchronous = FULL");
    db->exec("PRAGMA foreign_keys = ON");
    DCS_RETURN_IF_ERROR(MigrateSchema(*db));
    // Holders could not renew while no coordinator ran: give them a full lease from now.
    SQLite::Statement grace(*db,
                            "UPDATE leases SET deadline = max(deadline, ?) WHERE holder != ''");
    grace.bind(1, Micros(now + options.lease_duration));
    grace.exec();
    SQLite::Statement job_grace(
        *db, "UPDATE evaluation_jobs SET deadline = max(deadline, ?) WHERE holder != ''");
    job_grace.bind(1, Micros(now + options.lease_duration));
    job_grace.exec();
    return std::unique_ptr<Store>(new Store(
        std::make_unique<internal::StoreConnection>(std::move(db), options.lease_duration)));
  } catch (const SQLite::Exception& e) {
    const absl::Status error = internal::StoreError(path, e);
    return absl::Status(error.code(),
                        absl::StrCat("cannot open the coordinator database: ", error.message()));
  }
}

absl::StatusOr<int> Store::ExpireLeases(absl::Time now) {
  return connection_->Transaction([&](SQLite::Database& db) -> absl::StatusOr<int> {
    return connection_->ExpireLapsedLeases(db, now);
  });
}

int64_t Store::LeasesLapsed() { return connection_->LeasesLapsed(); }

absl::StatusOr<StoreCounts> Store::Counts() {
  return connection_->Transaction([&](SQLite::Database& db) -> absl::StatusOr<StoreCounts> {
    StoreCounts counts;
    for (const auto& [state, name] : kRunStateNames) {
      SQLite::Statement query(db, "SELECT count(*) FROM runs WHERE state = ?");
      query.bind(1, std::string(name));
      query.executeStep();
      counts.runs_by_state.emplace_back(state, query.getColumn(0).getInt64());
    }
    counts.free_learner_leases =
        db.execAndGet("SELECT count(*) FROM runs WHERE state = 'queued'").getInt64();
    counts.free_slot_leases =
        db.execAndGet("SELECT count(*) FROM leases s JOIN runs r ON r.number = s.run "
                        "WHERE s.slot >= 0 AND s.holder = '' AND r.state = 'running'")
            .getInt64();
    counts.free_evaluation_jobs =
        db.execAndGet("SELECT count(*) FROM evaluation_jobs j JOIN runs r ON r.number = j.run "
                        "WHERE j.done = 0 AND j.holder = '' "
                        "AND (r.state = 'running' OR j.policy_version < 0)")
            .getInt64();
    SQLite::Statement sweeps(
        db,
        "SELECT r.sweep, r.state, count(*), "
        "sum(CASE WHEN r.state IN ('queued', 'running') "
        "THEN max(0, r.total_timesteps - r.timesteps) ELSE 0 END) "
        "FROM runs r JOIN sweeps s ON s.number = r.sweep WHERE s.open != 0 OR EXISTS "
        "(SELECT 1 FROM runs a WHERE a.sweep = s.number AND a.state IN ('queued', 'running')) "
        "GROUP BY r.sweep, r.state ORDER BY r.sweep");
    while (sweeps.executeStep()) {
      const std::string sweep_id = SweepId(sweeps.getColumn(0).getInt64());
      if (counts.active_sweeps.empty() || counts.active_sweeps.back().sweep_id != sweep_id) {
        ActiveSweepCounts& sweep = counts.active_sweeps.emplace_back();
        sweep.sweep_id = sweep_id;
        for (const auto& [state, name] : kRunStateNames) sweep.runs_by_state.emplace_back(state, 0);
      }
      ActiveSweepCounts& sweep = counts.active_sweeps.back();
      // The schema's CHECK keeps states to the table's names: another means a damaged file.
      DCS_ASSIGN_OR_RETURN(const RunState state,
                           StoredValue(db, kRunStateNames, sweeps.getColumn(1).getString(),
                                       absl::StrCat("the state of a run of ", sweep_id)));
      sweep.runs_by_state[static_cast<int>(state)].second = sweeps.getColumn(2).getInt64();
      sweep.steps_remaining += sweeps.getColumn(3).getInt64();
    }
    return counts;
  });
}

absl::StatusOr<BackupCounts> Store::Backup(const std::string& path) {
  const std::string temporary = absl::StrCat(path, ".tmp.", ::getpid());
  // Everything after the copy's file exists: on an error, the temporary file goes.
  auto copy_into = [&](sqlite3* copy) -> absl::StatusOr<BackupCounts> {
    // Synced as it commits: the rename that follows publishes a whole file.
    if (const int rc = sqlite3_exec(copy, "PRAGMA synchronous = FULL", nullptr, nullptr, nullptr);
        rc != SQLITE_OK) {
      return BackupError(copy, rc, path);
    }
    return connection_->Locked([&](SQLite::Database& db) -> absl::StatusOr<BackupCounts> {
      sqlite3_backup* backup = sqlite3_backup_init(copy, "main", db.getHandle(), "main");
      if (backup == nullptr) return BackupError(copy, sqlite3_errcode(copy), path);
      // One step copies every page under one read transaction: a snapshot, since nothing else
      // writes while the store's lock is held.
      const int stepped = sqlite3_backup_step(backup, -1);
      const int finished = sqlite3_backup_finish(backup);
      if (stepped != SQLITE_DONE) return BackupError(copy, stepped, path);
      if (finished != SQLITE_OK) return BackupError(copy, finished, path);
      try {
        return BackupCounts{.runs = db.execAndGet("SELECT count(*) FROM runs").getInt64(),
                            .sweeps = db.execAndGet("SELECT count(*) FROM sweeps").getInt64(),
                            .studies = db.execAndGet("SELECT count(*) FROM studies").getInt64()};
      } catch (const SQLite::Exception& e) {
        return internal::StoreError(db.getFilename(), e);
      }
    });
  };
  // Created here, not by SQLite, whose errno after a failed open is that of its last fallback.
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return FileError(errno, "cannot back the store up to", path);
  ::close(fd);
  sqlite3* opened = nullptr;
  const int rc = sqlite3_open_v2(temporary.c_str(), &opened,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  std::unique_ptr<sqlite3, CloseConnection> copy(opened);
  absl::StatusOr<BackupCounts> counts =
      rc == SQLITE_OK ? copy_into(copy.get()) : BackupError(copy.get(), rc, path);
  if (counts.ok()) {
    if (const int closed = sqlite3_close(copy.release()); closed != SQLITE_OK) {
      counts = BackupError(nullptr, closed, path);
    }
  }
  if (!counts.ok()) {
    copy.reset();
    ::unlink(temporary.c_str());
    return counts;
  }
  DCS_RETURN_IF_ERROR(RenameDurably(temporary, path));
  return counts;
}

}  // namespace dcs::coordinator
