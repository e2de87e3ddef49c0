// Copyright 2026 The DCS Authors.
#include "coordinator/store_connection.h"

#include <sqlite3.h>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator::internal {

absl::Status StoreError(const std::string& path, const SQLite::Exception& error) {
  switch (error.getErrorCode()) {
    case SQLITE_FULL:  // the caller may make the same call again once there is room
      return absl::UnavailableError(absl::StrCat(
          path, ": the disk is full; nothing of this change was stored (", error.what(), ")"));
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      return store_rows::CorruptStore(path, error.what());
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return absl::UnavailableError(absl::StrCat(path, " is locked: ", error.what()));
    default:
      return absl::InternalError(absl::StrCat(path, ": ", error.what()));
  }
}

void RollBackIfActive(SQLite::Database& db) noexcept {
  if (sqlite3_get_autocommit(db.getHandle()) != 0) return;  // no transaction is open
  try {
    db.exec("ROLLBACK");
  } catch (const SQLite::Exception&) {  // the first error is the one to report
  }
}

StoreConnection::StoreConnection(std::unique_ptr<SQLite::Database> db,
                                 absl::Duration lease_duration)
    : db_(std::move(db)), lease_duration_(lease_duration) {}

absl::StatusOr<int> StoreConnection::ExpireLapsedLeases(SQLite::Database& db, absl::Time now) {
  DCS_ASSIGN_OR_RETURN(const int lapsed, store_rows::ExpireLapsed(db, now));
  leases_lapsing_ += lapsed;
  return lapsed;
}

int64_t StoreConnection::LeasesLapsed() {
  absl::MutexLock lock(&mu_);
  return leases_lapsed_;
}

}  // namespace dcs::coordinator::internal
