// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STORE_ROWS_H_
#define DCS_COORDINATOR_STORE_ROWS_H_

// The store's rows as its tables' implementation files share them (coordinator/store.h):
// ids, times, reading and writing a run's row, the one way a run's state changes, a held
// lease, lapsed leases, a study's row. Internal to the store: only its own .cc files include
// this header. Every function runs inside the caller's transaction
// (coordinator/store_connection.h), on the connection it is given.

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "common/enum_names.h"
#include "coordinator/run_state.h"
#include "coordinator/run_table.h"
#include "coordinator/study_table.h"

namespace dcs::coordinator::store_rows {

// Times are stored as microseconds since the Unix epoch, UTC.
inline int64_t Micros(absl::Time time) { return absl::ToUnixMicros(time); }
inline absl::Time FromMicros(int64_t micros) { return absl::FromUnixMicros(micros); }

// SQLite keeps no NaN (it stores NULL): a REAL column that may hold one is read and bound
// through these.
double DoubleOrNaN(const SQLite::Column& column);
void BindDoubleOrNull(SQLite::Statement& statement, int index, double value);

// "run-<n>" for row n, and back; NOT_FOUND for anything that is not a run id.
std::string RunId(int64_t number);
absl::StatusOr<int64_t> RunNumber(absl::string_view run_id);
// "sweep-<n>" for row n, and back; NOT_FOUND for anything that is not a sweep id.
std::string SweepId(int64_t number);
absl::StatusOr<int64_t> SweepNumber(absl::string_view sweep_id);
// "study-<n>" for row n, and back; NOT_FOUND for anything that is not a study id.
std::string StudyId(int64_t number);
absl::StatusOr<int64_t> StudyNumber(absl::string_view study_id);

// The run `run_id`. NOT_FOUND if there is none.
absl::StatusOr<RunRecord> FindRun(SQLite::Database& db, absl::string_view run_id);
// Every run matching `where` (an SQL condition on the runs table; with `bind`, its one
// parameter), oldest first.
std::vector<RunRecord> FindRuns(SQLite::Database& db, absl::string_view where,
                                std::optional<int64_t> bind = std::nullopt);

// Queues a new run (its row and its leases: the learner's and one per env slot), as part of
// sweep `sweep` (trial `trial`) or of none. Returns its row number.
int64_t InsertRun(SQLite::Database& db, const RunSubmission& submission,
                  std::optional<int64_t> sweep, std::optional<int> trial, absl::Time now);

// Moves a run to `to` through the one transition table (coordinator/run_state.h).
absl::Status SetRunState(SQLite::Database& db, const RunRecord& run, RunState to,
                         absl::string_view error, absl::Time now);

// Frees leases of run `number`: every slot lease, and the learner lease too if `learner`.
void FreeLeases(SQLite::Database& db, int64_t number, bool learner);

// Drops the policies of run `number`'s own evaluations: it ended, nothing evaluates them any
// more. Its grid evaluations' (negative policy versions) are a client's, evaluated still.
void DropEvaluationWeights(SQLite::Database& db, int64_t number);

// Cancels a queued or running run: its leases are freed and its policies dropped.
// FAILED_PRECONDITION if it already ended.
absl::Status CancelRunRow(SQLite::Database& db, const RunRecord& run, absl::string_view reason,
                          absl::Time now);

// OK if run `run` may be removed for good: it ended, and no grid evaluation of it is still
// open. FAILED_PRECONDITION naming what still works on it, and `how_to_stop` it when it still
// runs (the command that cancels it: the run's own, or its sweep's).
absl::Status CheckRemovable(SQLite::Database& db, const RunRecord& run,
                            absl::string_view how_to_stop);
// Deletes row `number` of `table` and, before it, the rows of `children` (in that order) whose
// `column` is `number`: the connection enforces foreign keys, so a row goes after those that
// refer to it.
void DeleteRowAndChildren(SQLite::Database& db, absl::string_view table, int64_t number,
                          absl::string_view column,
                          std::initializer_list<absl::string_view> children);
// Deletes run `number` and every row that hangs off it: its leases, its checkpoints' index,
// its evaluations (grid evaluations too) with their jobs and results.
void DeleteRunRows(SQLite::Database& db, int64_t number);

// OK if `key` names the lease as it is held now: same epoch, still held, run not ended.
// FAILED_PRECONDITION saying which it is not; NOT_FOUND for an unknown run or slot.
absl::Status CheckHeld(SQLite::Database& db, const LeaseKey& key);

// Frees every lease whose deadline passed at `now` (learner leases, whose runs go back to the
// queue with their slot leases freed; slot leases; evaluation jobs). Returns how many lapsed.
absl::StatusOr<int> ExpireLapsed(SQLite::Database& db, absl::Time now);

// Pins run `number`'s numeric fingerprint of one role (`column`: learner_numerics or
// actor_numerics) to `numerics`: the workers that may take its leases of that role from now on.
void PinNumerics(SQLite::Database& db, absl::string_view column, int64_t number,
                 absl::string_view numerics);

// Studies (coordinator/study_table.cc). INVALID_ARGUMENT if CreateStudy would refuse
// `submission` (checked before its transaction).
absl::Status CheckStudySubmission(const StudySubmission& submission);
// Inserts a checked study, driven by sweep `sweep` or by none; returns its row number.
int64_t InsertStudy(SQLite::Database& db, const StudySubmission& submission,
                    std::optional<int64_t> sweep, absl::Time now);
// Fails the running trials of the study sweep `sweep` drives (it was cancelled).
void FailRunningStudyTrials(SQLite::Database& db, int64_t sweep, absl::Time now);
// Deletes study `number` and its trials with their values, reports and rungs.
void DeleteStudyRows(SQLite::Database& db, int64_t number);

// DATA_LOSS naming the store at `path`: it holds `what`, which its schema or its writers
// forbid, so the file was damaged (never the caller's fault, never to be indexed with).
absl::Status CorruptStore(const std::string& path, absl::string_view what);

// The value the name stored as `what` stands for in `names`; CorruptStore for any other name,
// which the schema's CHECK constraints keep out of an undamaged file.
template <typename E, size_t N>
absl::StatusOr<E> StoredValue(SQLite::Database& db, const EnumName<E> (&names)[N],
                              const std::string& name, absl::string_view what) {
  if (const std::optional<E> value = FindByName(names, name); value.has_value()) return *value;
  return CorruptStore(db.getFilename(), absl::StrCat(what, " is '", name,
                                                     "', which is not one of ", ListNames(names)));
}

}  // namespace dcs::coordinator::store_rows

#endif  // DCS_COORDINATOR_STORE_ROWS_H_
