// Copyright 2026 The DCS Authors.
#include "coordinator/checkpoint_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {

using namespace store_rows;  // NOLINT: the store's own rows

absl::Status CheckpointTable::RecordCheckpoint(const LeaseKey& key,
                                               const CheckpointRecord& checkpoint, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    const int64_t number = *RunNumber(key.run_id);
    SQLite::Statement insert(db, "INSERT OR REPLACE INTO checkpoints (run, name, timesteps, "
                                 "sha256, created_at) VALUES (?, ?, ?, ?, ?)");
    insert.bind(1, number);
    insert.bind(2, checkpoint.name);
    insert.bind(3, checkpoint.timesteps);
    insert.bind(4, checkpoint.sha256);
    insert.bind(5, Micros(now));
    insert.exec();
    SQLite::Statement update(db, "UPDATE runs SET checkpoint = ?, updated_at = ? "
                                 "WHERE number = ?");
    update.bind(1, checkpoint.name);
    update.bind(2, Micros(now));
    update.bind(3, number);
    update.exec();
    return absl::OkStatus();
  });
}

absl::StatusOr<std::vector<CheckpointRecord>> CheckpointTable::ListCheckpoints(
    absl::string_view run_id) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<CheckpointRecord>> {
        DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(run_id));
        SQLite::Statement query(db, "SELECT name, timesteps, sha256 FROM checkpoints "
                                    "WHERE run = ? ORDER BY timesteps");
        query.bind(1, number);
        std::vector<CheckpointRecord> checkpoints;
        while (query.executeStep()) {
          checkpoints.push_back({.name = query.getColumn(0).getString(),
                                 .timesteps = query.getColumn(1).getInt64(),
                                 .sha256 = query.getColumn(2).getString()});
        }
        return checkpoints;
      });
}

}  // namespace dcs::coordinator
