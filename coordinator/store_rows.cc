// Copyright 2026 The DCS Authors.
#include "coordinator/store_rows.h"

#include <sqlite3.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/run_state.h"

namespace dcs::coordinator::store_rows {
namespace {

// "<kind>-<n>" for row n of the kind's table ("run-3"), and back: NOT_FOUND naming the id for
// anything that is not one.
std::string RowId(absl::string_view kind, int64_t number) {
  return absl::StrCat(kind, "-", number);
}

absl::StatusOr<int64_t> RowNumber(absl::string_view id, absl::string_view kind) {
  int64_t number = 0;
  absl::string_view digits = id;
  if (!absl::ConsumePrefix(&digits, kind) || !absl::ConsumePrefix(&digits, "-") ||
      !absl::SimpleAtoi(digits, &number)) {
    return absl::NotFoundError(
        absl::StrCat("no ", kind, " '", id, "' (", kind, " ids look like ", kind, "-1)"));
  }
  return number;
}

std::string LeaseName(const LeaseKey& key) {
  return key.slot == kLearnerSlot ? absl::StrCat("the learner lease of ", key.run_id)
                                  : absl::StrCat("the lease of slot ", key.slot, " of ",
                                                 key.run_id);
}

constexpr char kRunColumns[] =
    "number, request_id, config, seed, env, n_envs, total_timesteps, state, error, "
    "learner_numerics, actor_numerics, "
    "timesteps, policy_version, steps_per_second, recent_return, avg_combined, evaluation_step, "
    "checkpoint, created_at, updated_at, sweep, trial";

RunRecord ReadRun(SQLite::Statement& row) {
  RunRecord run;
  run.id = RunId(row.getColumn(0).getInt64());
  run.submission = {.request_id = row.getColumn(1).getString(),
                    .config = row.getColumn(2).getString(),
                    .seed = static_cast<uint64_t>(row.getColumn(3).getInt64()),
                    .env = row.getColumn(4).getString(),
                    .n_envs = row.getColumn(5).getInt(),
                    .total_timesteps = row.getColumn(6).getInt64()};
  const std::string state = row.getColumn(7).getString();
  const std::optional<RunState> known = FindByName(kRunStateNames, state);
  if (!known.has_value()) {
    // The schema's CHECK keeps other names out: only a damaged file holds one. Thrown as
    // SQLite's own corruption, which the store's edge reports as DATA_LOSS (StoreError).
    throw SQLite::Exception(absl::StrCat(run.id, " has an unknown state '", state, "'"),
                            SQLITE_CORRUPT);
  }
  run.state = *known;
  run.error = row.getColumn(8).getString();
  run.learner_numerics = row.getColumn(9).getString();
  run.actor_numerics = row.getColumn(10).getString();
  run.progress = {.timesteps = row.getColumn(11).getInt64(),
                  .policy_version = row.getColumn(12).getInt64(),
                  .steps_per_second = row.getColumn(13).getDouble(),
                  .recent_return = DoubleOrNaN(row.getColumn(14))};
  if (!row.getColumn(15).isNull()) run.progress.avg_combined = row.getColumn(15).getDouble();
  if (!row.getColumn(16).isNull()) run.progress.evaluation_step = row.getColumn(16).getInt64();
  run.checkpoint = row.getColumn(17).getString();
  run.created_at = FromMicros(row.getColumn(18).getInt64());
  run.updated_at = FromMicros(row.getColumn(19).getInt64());
  if (!row.getColumn(20).isNull()) run.sweep_id = SweepId(row.getColumn(20).getInt64());
  if (!row.getColumn(21).isNull()) run.trial = row.getColumn(21).getInt();
  return run;
}

}  // namespace

double DoubleOrNaN(const SQLite::Column& column) {
  return column.isNull() ? std::numeric_limits<double>::quiet_NaN() : column.getDouble();
}

void BindDoubleOrNull(SQLite::Statement& statement, int index, double value) {
  if (std::isnan(value)) {
    statement.bind(index);
  } else {
    statement.bind(index, value);
  }
}

std::string RunId(int64_t number) { return RowId("run", number); }
absl::StatusOr<int64_t> RunNumber(absl::string_view run_id) { return RowNumber(run_id, "run"); }
std::string SweepId(int64_t number) { return RowId("sweep", number); }
absl::StatusOr<int64_t> SweepNumber(absl::string_view sweep_id) {
  return RowNumber(sweep_id, "sweep");
}
std::string StudyId(int64_t number) { return RowId("study", number); }
absl::StatusOr<int64_t> StudyNumber(absl::string_view study_id) {
  return RowNumber(study_id, "study");
}

absl::StatusOr<RunRecord> FindRun(SQLite::Database& db, absl::string_view run_id) {
  DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(run_id));
  SQLite::Statement query(db, absl::StrCat("SELECT ", kRunColumns, " FROM runs WHERE number = ?"));
  query.bind(1, number);
  if (!query.executeStep()) return absl::NotFoundError(absl::StrCat("no run ", run_id));
  return ReadRun(query);
}

std::vector<RunRecord> FindRuns(SQLite::Database& db, absl::string_view where,
                                std::optional<int64_t> bind) {
  SQLite::Statement query(
      db, absl::StrCat("SELECT ", kRunColumns, " FROM runs WHERE ", where, " ORDER BY number"));
  if (bind.has_value()) query.bind(1, *bind);
  std::vector<RunRecord> runs;
  while (query.executeStep()) runs.push_back(ReadRun(query));
  return runs;
}

int64_t InsertRun(SQLite::Database& db, const RunSubmission& submission,
                  std::optional<int64_t> sweep, std::optional<int> trial, absl::Time now) {
  SQLite::Statement insert(db,
                           "INSERT INTO runs (request_id, config, seed, env, n_envs, "
                           "total_timesteps, state, created_at, updated_at, sweep, trial) "
                           "VALUES (?, ?, ?, ?, ?, ?, 'queued', ?, ?, ?, ?) RETURNING number");
  insert.bind(1, submission.request_id);
  insert.bind(2, submission.config);
  insert.bind(3, static_cast<int64_t>(submission.seed));
  insert.bind(4, submission.env);
  insert.bind(5, submission.n_envs);
  insert.bind(6, submission.total_timesteps);
  insert.bind(7, Micros(now));
  insert.bind(8, Micros(now));
  if (sweep.has_value()) insert.bind(9, *sweep);
  if (trial.has_value()) insert.bind(10, *trial);
  insert.executeStep();
  const int64_t number = insert.getColumn(0).getInt64();
  insert.reset();
  SQLite::Statement lease(db, "INSERT INTO leases (run, slot) VALUES (?, ?)");
  for (int slot = kLearnerSlot; slot < submission.n_envs; ++slot) {
    lease.bind(1, number);
    lease.bind(2, slot);
    lease.exec();
    lease.reset();
  }
  return number;
}

absl::Status SetRunState(SQLite::Database& db, const RunRecord& run, RunState to,
                         absl::string_view error, absl::Time now) {
  DCS_RETURN_IF_ERROR(CheckTransition(run.id, run.state, to));
  SQLite::Statement update(db, "UPDATE runs SET state = ?, error = ?, updated_at = ? "
                               "WHERE number = ?");
  update.bind(1, std::string(NameOf(kRunStateNames, to)));
  update.bind(2, std::string(error));
  update.bind(3, Micros(now));
  update.bind(4, *RunNumber(run.id));
  update.exec();
  return absl::OkStatus();
}

void FreeLeases(SQLite::Database& db, int64_t number, bool learner) {
  SQLite::Statement update(db, learner ? "UPDATE leases SET holder = '', address = '', "
                                         "deadline = 0 WHERE run = ?"
                                       : "UPDATE leases SET holder = '', address = '', "
                                         "deadline = 0 WHERE run = ? AND slot >= 0");
  update.bind(1, number);
  update.exec();
}

void DropEvaluationWeights(SQLite::Database& db, int64_t number) {
  SQLite::Statement update(db, "UPDATE evaluations SET weights = x'' WHERE run = ? AND "
                               "policy_version >= 0");
  update.bind(1, number);
  update.exec();
}

absl::Status CancelRunRow(SQLite::Database& db, const RunRecord& run, absl::string_view reason,
                          absl::Time now) {
  DCS_RETURN_IF_ERROR(SetRunState(db, run, RunState::kCancelled, reason, now));
  FreeLeases(db, *RunNumber(run.id), /*learner=*/true);
  DropEvaluationWeights(db, *RunNumber(run.id));
  return absl::OkStatus();
}

absl::Status CheckRemovable(SQLite::Database& db, const RunRecord& run,
                            absl::string_view how_to_stop) {
  if (!IsTerminal(run.state)) {
    return absl::FailedPreconditionError(absl::StrCat(run.id, " is ",
                                                      NameOf(kRunStateNames, run.state),
                                                      ": stop it first with ", how_to_stop));
  }
  SQLite::Statement open(db, "SELECT count(*) FROM evaluation_jobs WHERE run = ? AND "
                             "policy_version < 0 AND done = 0");
  open.bind(1, *RunNumber(run.id));
  open.executeStep();
  if (const int64_t cells = open.getColumn(0).getInt64(); cells > 0) {
    // A client waits for it, and actors may hold its cells.
    return absl::FailedPreconditionError(absl::StrCat(
        run.id, " has a grid evaluation (`dcs eval --on-actors`) with ", cells,
        " cells still to evaluate: remove it once they are in"));
  }
  return absl::OkStatus();
}

void DeleteRowAndChildren(SQLite::Database& db, absl::string_view table, int64_t number,
                          absl::string_view column,
                          std::initializer_list<absl::string_view> children) {
  for (absl::string_view child : children) {
    SQLite::Statement remove(db, absl::StrCat("DELETE FROM ", child, " WHERE ", column, " = ?"));
    remove.bind(1, number);
    remove.exec();
  }
  SQLite::Statement remove(db, absl::StrCat("DELETE FROM ", table, " WHERE number = ?"));
  remove.bind(1, number);
  remove.exec();
}

void DeleteRunRows(SQLite::Database& db, int64_t number) {
  DeleteRowAndChildren(db, "runs", number, "run",
                       {"evaluation_returns", "evaluation_jobs", "grid_evaluations",
                        "evaluations", "checkpoints", "leases"});
}

absl::Status CorruptStore(const std::string& path, absl::string_view what) {
  return absl::DataLossError(absl::StrCat(path, " is corrupt: ", what));
}

absl::Status CheckHeld(SQLite::Database& db, const LeaseKey& key) {
  DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, key.run_id));
  SQLite::Statement query(db, "SELECT epoch, holder FROM leases WHERE run = ? AND slot = ?");
  query.bind(1, *RunNumber(key.run_id));
  query.bind(2, key.slot);
  if (!query.executeStep()) {
    return absl::NotFoundError(absl::StrCat(key.run_id, " has no slot ", key.slot));
  }
  if (IsTerminal(run.state)) {
    return absl::FailedPreconditionError(absl::StrCat(
        LeaseName(key), " is void: the run is ", NameOf(kRunStateNames, run.state)));
  }
  const int64_t epoch = query.getColumn(0).getInt64();
  if (epoch != key.epoch) {
    return absl::FailedPreconditionError(absl::StrCat(LeaseName(key), " moved: epoch ", epoch,
                                                      " was granted after epoch ", key.epoch));
  }
  if (query.getColumn(1).getString().empty()) {
    return absl::FailedPreconditionError(
        absl::StrCat(LeaseName(key), " (epoch ", key.epoch, ") lapsed and went back to the queue"));
  }
  return absl::OkStatus();
}

absl::StatusOr<int> ExpireLapsed(SQLite::Database& db, absl::Time now) {
  // Learner leases first: their runs go back to the queue with every slot lease freed.
  SQLite::Statement learners(db, "SELECT run FROM leases WHERE slot = -1 AND holder != '' AND "
                                 "deadline < ?");
  learners.bind(1, Micros(now));
  std::vector<int64_t> requeued;
  while (learners.executeStep()) requeued.push_back(learners.getColumn(0).getInt64());
  for (int64_t number : requeued) {
    FreeLeases(db, number, /*learner=*/true);
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, RunId(number)));
    DCS_RETURN_IF_ERROR(SetRunState(db, run, RunState::kQueued, "", now));
  }
  SQLite::Statement slots(db, "UPDATE leases SET holder = '', address = '', deadline = 0 "
                              "WHERE slot >= 0 AND holder != '' AND deadline < ?");
  slots.bind(1, Micros(now));
  SQLite::Statement jobs(db, "UPDATE evaluation_jobs SET holder = '', deadline = 0 "
                             "WHERE done = 0 AND holder != '' AND deadline < ?");
  jobs.bind(1, Micros(now));
  return static_cast<int>(requeued.size()) + slots.exec() + jobs.exec();
}

void PinNumerics(SQLite::Database& db, absl::string_view column, int64_t number,
                 absl::string_view numerics) {
  SQLite::Statement pin(db, absl::StrCat("UPDATE runs SET ", column, " = ? WHERE number = ?"));
  pin.bind(1, std::string(numerics));
  pin.bind(2, number);
  pin.exec();
}

}  // namespace dcs::coordinator::store_rows
