// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STORE_SCHEMA_H_
#define DCS_COORDINATOR_STORE_SCHEMA_H_

// The coordinator database's schema, as forward-only migrations: migration i takes the schema
// from version i to i + 1 (PRAGMA user_version holds the version). A released migration is
// never edited; a change is a new one appended.

#include "absl/status/status.h"

namespace SQLite {
class Database;
}  // namespace SQLite

namespace dcs::coordinator {

// The schema version this build writes.
int CurrentSchemaVersion();

// Brings `db` to version `target` (tests build older databases with a lower one), each
// migration in its own transaction. FAILED_PRECONDITION for a database of a newer version than
// this build's; DATA_LOSS for a negative version (a damaged file). Throws SQLite::Exception on
// SQLite errors (the caller, Store::Open, maps them).
absl::Status MigrateSchema(SQLite::Database& db, int target = CurrentSchemaVersion());

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STORE_SCHEMA_H_
