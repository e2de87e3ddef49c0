// Copyright 2026 The DCS Authors.
// Store::Counts (coordinator/store_counts.h), apart from the rest of the store: it is what
// every scrape of the coordinator's metrics costs, one query per kind of series.
#include "coordinator/store_counts.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "coordinator/store.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

// The sweeps shown: with work ahead, or among the kRecentSweeps most recent.
const std::string kShownSweeps = absl::StrCat(
    "SELECT s.number FROM sweeps s WHERE s.open != 0 "
    "OR s.number IN (SELECT number FROM sweeps ORDER BY number DESC LIMIT ",
    kRecentSweeps,
    ") OR EXISTS (SELECT 1 FROM runs a WHERE a.sweep = s.number "
    "AND a.state IN ('queued', 'running'))");

// The column's time, or nullopt for NULL.
std::optional<absl::Time> TimeOrNull(const SQLite::Column& column) {
  if (column.isNull()) return std::nullopt;
  return FromMicros(column.getInt64());
}

// The runs queued or running, with their trials, scores and checkpoint times, in one query.
absl::StatusOr<std::vector<LiveRun>> LiveRuns(SQLite::Database& db) {
  SQLite::Statement query(
      db,
      absl::StrCat(
          "SELECT r.number, r.sweep, t.condition, t.observe, r.state, r.timesteps, "
          "r.total_timesteps, r.latest_evaluation_step, r.latest_avg_combined, "
          "r.latest_id_return, r.latest_ood_low_return, r.latest_ood_high_return, "
          "r.best_evaluation_step, r.best_avg_combined, "
          "(SELECT max(c.created_at) FROM checkpoints c WHERE c.run = r.number), "
          "nullif(l.granted_at, 0) "
          "FROM runs r LEFT JOIN trials t ON t.sweep = r.sweep AND t.trial = r.trial "
          "LEFT JOIN leases l ON l.run = r.number AND l.slot = ",
          kLearnerSlot, " WHERE r.state IN ('queued', 'running') ORDER BY r.number"));
  std::vector<LiveRun> runs;
  while (query.executeStep()) {
    LiveRun& run = runs.emplace_back();
    run.run_id = RunId(query.getColumn(0).getInt64());
    if (!query.getColumn(1).isNull()) run.sweep_id = SweepId(query.getColumn(1).getInt64());
    run.condition = query.getColumn(2).getString();  // NULL reads as empty
    run.observe = query.getColumn(3).getString();
    DCS_ASSIGN_OR_RETURN(run.state,
                         StoredValue(db, kRunStateNames, query.getColumn(4).getString(),
                                     absl::StrCat("the state of ", run.run_id)));
    run.timesteps = query.getColumn(5).getInt64();
    run.total_timesteps = query.getColumn(6).getInt64();
    if (!query.getColumn(7).isNull()) {
      run.scores = EvaluationScores{
          .latest_step = query.getColumn(7).getInt64(),
          .latest_avg_combined = DoubleOrNaN(query.getColumn(8)),
          .latest_id_return = DoubleOrNaN(query.getColumn(9)),
          .latest_ood_low_return = DoubleOrNaN(query.getColumn(10)),
          .latest_ood_high_return = DoubleOrNaN(query.getColumn(11)),
          .best_step = query.getColumn(12).isNull() ? 0 : query.getColumn(12).getInt64(),
          .best_avg_combined = DoubleOrNaN(query.getColumn(13))};
    }
    if (run.state == RunState::kRunning) {
      run.checkpointed_at = TimeOrNull(query.getColumn(14));
      if (!run.checkpointed_at.has_value()) run.checkpointed_at = TimeOrNull(query.getColumn(15));
    }
  }
  return runs;
}

// The shown sweeps' runs by state and steps remaining, then each one's best trial.
absl::StatusOr<std::vector<SweepCounts>> ShownSweeps(SQLite::Database& db) {
  std::vector<SweepCounts> sweeps;
  SQLite::Statement counts(
      db, absl::StrCat("SELECT r.sweep, r.state, count(*), "
                       "sum(CASE WHEN r.state IN ('queued', 'running') "
                       "THEN max(0, r.total_timesteps - r.timesteps) ELSE 0 END) "
                       "FROM runs r WHERE r.sweep IN (",
                       kShownSweeps, ") GROUP BY r.sweep, r.state ORDER BY r.sweep"));
  std::map<int64_t, size_t> index;  // sweep number -> its place in `sweeps`
  while (counts.executeStep()) {
    const int64_t number = counts.getColumn(0).getInt64();
    if (sweeps.empty() || index.rbegin()->first != number) {
      index[number] = sweeps.size();
      SweepCounts& sweep = sweeps.emplace_back();
      sweep.sweep_id = SweepId(number);
      for (const auto& [state, name] : kRunStateNames) sweep.runs_by_state.emplace_back(state, 0);
    }
    SweepCounts& sweep = sweeps.back();
    // The schema's CHECK keeps states to the table's names: another means a damaged file.
    DCS_ASSIGN_OR_RETURN(const RunState state,
                         StoredValue(db, kRunStateNames, counts.getColumn(1).getString(),
                                     absl::StrCat("the state of a run of ", sweep.sweep_id)));
    sweep.runs_by_state[static_cast<int>(state)].second = counts.getColumn(2).getInt64();
    sweep.steps_remaining += counts.getColumn(3).getInt64();
  }

  // Each shown sweep's completed runs' last avg_combined, by trial in trial order, as `dcs
  // watch` scores its trials (a NaN is stored as NULL, and so not counted, as there).
  SQLite::Statement scores(
      db, absl::StrCat("SELECT r.sweep, r.trial, t.condition, t.observe, r.avg_combined "
                       "FROM runs r JOIN trials t ON t.sweep = r.sweep AND t.trial = r.trial "
                       "WHERE r.state = 'completed' AND r.avg_combined IS NOT NULL "
                       "AND r.sweep IN (",
                       kShownSweeps, ") ORDER BY r.sweep, r.trial"));
  struct Trials {
    std::vector<TrialScore> names;  // score unset
    std::vector<std::vector<double>> last;
    int64_t trial = -1;  // of the last entry
  };
  std::map<int64_t, Trials> trials;  // by sweep number
  while (scores.executeStep()) {
    Trials& sweep = trials[scores.getColumn(0).getInt64()];
    const int64_t trial = scores.getColumn(1).getInt64();
    if (sweep.names.empty() || sweep.trial != trial) {
      sweep.trial = trial;
      sweep.names.push_back({.condition = scores.getColumn(2).getString(),
                             .observe = scores.getColumn(3).getString()});
      sweep.last.emplace_back();
    }
    sweep.last.back().push_back(scores.getColumn(4).getDouble());
  }
  for (auto& [number, sweep] : trials) {
    const auto shown = index.find(number);
    const std::optional<HighestIqmGroup> best = HighestIqm(sweep.last);
    if (shown == index.end() || !best.has_value()) continue;
    TrialScore& trial = sweeps[shown->second].best.emplace(std::move(sweep.names[best->index]));
    trial.score = best->iqm;
  }
  return sweeps;
}

// The size of the database file at `path` and of its write-ahead log; a file missing counts 0.
int64_t StoreBytes(const std::string& path) {
  int64_t bytes = 0;
  for (const std::string& file : {path, absl::StrCat(path, "-wal")}) {
    std::error_code error;
    const uintmax_t size = std::filesystem::file_size(file, error);
    if (!error) bytes += static_cast<int64_t>(size);
  }
  return bytes;
}

}  // namespace

absl::StatusOr<StoreCounts> Store::Counts() {
  return connection_->Transaction([&](SQLite::Database& db) -> absl::StatusOr<StoreCounts> {
    StoreCounts counts;
    SQLite::Statement states(db, "SELECT state, count(*) FROM runs GROUP BY state");
    for (const auto& [state, name] : kRunStateNames) counts.runs_by_state.emplace_back(state, 0);
    while (states.executeStep()) {
      DCS_ASSIGN_OR_RETURN(const RunState state,
                           StoredValue(db, kRunStateNames, states.getColumn(0).getString(),
                                       "the state of a run"));
      counts.runs_by_state[static_cast<int>(state)].second = states.getColumn(1).getInt64();
    }
    counts.free_learner_leases = counts.runs_by_state[static_cast<int>(RunState::kQueued)].second;
    counts.free_slot_leases =
        db.execAndGet("SELECT count(*) FROM leases s JOIN runs r ON r.number = s.run "
                      "WHERE s.slot >= 0 AND s.holder = '' AND r.state = 'running'")
            .getInt64();
    SQLite::Statement jobs(
        db, "SELECT count(*), min(e.created_at) FROM evaluation_jobs j "
            "JOIN runs r ON r.number = j.run "
            "JOIN evaluations e ON e.run = j.run AND e.policy_version = j.policy_version "
            "WHERE j.done = 0 AND j.holder = '' "
            "AND (r.state = 'running' OR j.policy_version < 0)");
    jobs.executeStep();
    counts.free_evaluation_jobs = jobs.getColumn(0).getInt64();
    counts.oldest_free_evaluation = TimeOrNull(jobs.getColumn(1));
    DCS_ASSIGN_OR_RETURN(counts.live_runs, LiveRuns(db));
    DCS_ASSIGN_OR_RETURN(counts.sweeps, ShownSweeps(db));
    counts.store_bytes = StoreBytes(db.getFilename());
    return counts;
  });
}

}  // namespace dcs::coordinator
