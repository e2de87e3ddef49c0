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
