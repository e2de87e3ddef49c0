// Copyright 2026 The DCS Authors.
#include "coordinator/checkpoint_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <cmath>

#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {

using namespace store_rows;  // NOLINT: the store's own rows

namespace {

// Records `scores` of run `number`: the latest evaluation if later than the one it has, the best
// if higher (a NaN avg_combined is never the best).
void RecordScores(SQLite::Database& db, int64_t number, const EvaluationScores& scores) {
  SQLite::Statement latest(
      db, "UPDATE runs SET latest_evaluation_step = ?, latest_avg_combined = ?, "
          "latest_id_return = ?, latest_ood_low_return = ?, latest_ood_high_return = ? "
          "WHERE number = ? AND (latest_evaluation_step IS NULL OR latest_evaluation_step < ?)");
  latest.bind(1, scores.latest_step);
  BindDoubleOrNull(latest, 2, scores.latest_avg_combined);
  BindDoubleOrNull(latest, 3, scores.latest_id_return);
  BindDoubleOrNull(latest, 4, scores.latest_ood_low_return);
  BindDoubleOrNull(latest, 5, scores.latest_ood_high_return);
  latest.bind(6, number);
  latest.bind(7, scores.latest_step);
  latest.exec();
  if (std::isnan(scores.best_avg_combined)) return;
  SQLite::Statement best(
      db, "UPDATE runs SET best_evaluation_step = ?, best_avg_combined = ? "
          "WHERE number = ? AND (best_avg_combined IS NULL OR best_avg_combined < ?)");
  best.bind(1, scores.best_step);
  best.bind(2, scores.best_avg_combined);
  best.bind(3, number);
  best.bind(4, scores.best_avg_combined);
  best.exec();
}

}  // namespace

absl::Status CheckpointTable::RecordCheckpoint(const LeaseKey& key,
                                               const CheckpointRecord& checkpoint,
                                               const std::optional<EvaluationScores>& scores,
                                               absl::Time now) {
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
    if (scores.has_value()) RecordScores(db, number, *scores);
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
