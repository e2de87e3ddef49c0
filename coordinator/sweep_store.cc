// Copyright 2026 The DCS Authors.
//
// RunStore's sweeps (coordinator/run_store.h): a sweep's row, its trials, and its runs, which
// are ordinary runs that name their sweep and trial.

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/run_state.h"
#include "coordinator/run_store.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

absl::StatusOr<SweepRecord> FindSweep(SQLite::Database& db, absl::string_view sweep_id) {
  DCS_ASSIGN_OR_RETURN(const int64_t number, SweepNumber(sweep_id));
  SQLite::Statement query(db, "SELECT request_id, name, spec, seeds, cancelled, created_at, "
                              "updated_at FROM sweeps WHERE number = ?");
  query.bind(1, number);
  if (!query.executeStep()) return absl::NotFoundError(absl::StrCat("no sweep ", sweep_id));
  SweepRecord sweep{.id = SweepId(number),
                    .request_id = query.getColumn(0).getString(),
                    .name = query.getColumn(1).getString(),
                    .spec = query.getColumn(2).getString(),
                    .seeds = query.getColumn(3).getInt(),
                    .created_at = FromMicros(query.getColumn(5).getInt64()),
                    .updated_at = FromMicros(query.getColumn(6).getInt64())};
  const bool cancelled = query.getColumn(4).getInt() != 0;
  query.reset();

  SQLite::Statement trials(db, "SELECT condition, family, observe FROM trials WHERE sweep = ? "
                               "ORDER BY trial");
  trials.bind(1, number);
  while (trials.executeStep()) {
    sweep.trials.push_back({.condition = trials.getColumn(0).getString(),
                            .family = trials.getColumn(1).getString(),
                            .observe = trials.getColumn(2).getString()});
  }
  for (const auto& [state, name] : kRunStateNames) {
    SQLite::Statement count(db, "SELECT count(*) FROM runs WHERE sweep = ? AND state = ?");
    count.bind(1, number);
    count.bind(2, std::string(name));
    count.executeStep();
    sweep.runs_by_state.emplace_back(state, count.getColumn(0).getInt64());
  }
  sweep.state = SweepStateOf(sweep.runs_by_state, cancelled);
  return sweep;
}

// The runs of sweep `number` in `state`.
std::vector<RunRecord> SweepRunsIn(SQLite::Database& db, int64_t number, RunState state) {
  return FindRuns(db, absl::StrCat("sweep = ? AND state = '", NameOf(kRunStateNames, state), "'"),
                  number);
}

void TouchSweep(SQLite::Database& db, int64_t number, absl::Time now) {
  SQLite::Statement touch(db, "UPDATE sweeps SET updated_at = ? WHERE number = ?");
  touch.bind(1, Micros(now));
  touch.bind(2, number);
  touch.exec();
}

}  // namespace

absl::StatusOr<SweepRecord> RunStore::SubmitSweep(const SweepSubmission& submission,
                                                  absl::Time now) {
  if (submission.request_id.empty()) {
    return absl::InvalidArgumentError("a sweep submission needs a request id");
  }
  if (submission.trials.empty()) return absl::InvalidArgumentError("the sweep has no trials");
  if (submission.seeds < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("the sweep has ", submission.seeds, " seeds; it needs at least one"));
  }
  for (const SweepSubmission::Run& run : submission.runs) {
    if (run.trial < 0 || run.trial >= static_cast<int>(submission.trials.size())) {
      return absl::InvalidArgumentError(absl::StrCat("a run of the sweep names trial ", run.trial,
                                                     "; it has ", submission.trials.size()));
    }
    if (run.run.request_id.empty() || run.run.config.empty() || run.run.n_envs < 1) {
      return absl::InvalidArgumentError(
          absl::StrCat("run ", run.run.request_id, " of trial ", run.trial,
                       " needs a request id, a config and at least one env slot"));
    }
  }
  return Transaction([&]() -> absl::StatusOr<SweepRecord> {
    SQLite::Statement existing(*db_, "SELECT number FROM sweeps WHERE request_id = ?");
    existing.bind(1, submission.request_id);
    if (existing.executeStep()) return FindSweep(*db_, SweepId(existing.getColumn(0).getInt64()));

    SQLite::Statement insert(*db_, "INSERT INTO sweeps (request_id, name, spec, seeds, "
                                   "created_at, updated_at) VALUES (?, ?, ?, ?, ?, ?) "
                                   "RETURNING number");
    insert.bind(1, submission.request_id);
    insert.bind(2, submission.name);
    insert.bind(3, submission.spec);
    insert.bind(4, submission.seeds);
    insert.bind(5, Micros(now));
    insert.bind(6, Micros(now));
    insert.executeStep();
    const int64_t number = insert.getColumn(0).getInt64();
    insert.reset();

    SQLite::Statement trial(*db_, "INSERT INTO trials (sweep, trial, condition, family, observe) "
                                  "VALUES (?, ?, ?, ?, ?)");
    for (size_t i = 0; i < submission.trials.size(); ++i) {
      trial.bind(1, number);
      trial.bind(2, static_cast<int>(i));
      trial.bind(3, submission.trials[i].condition);
      trial.bind(4, submission.trials[i].family);
      trial.bind(5, submission.trials[i].observe);
      trial.exec();
      trial.reset();
    }
    for (const SweepSubmission::Run& run : submission.runs) {
      InsertRun(*db_, run.run, number, run.trial, now);
    }
    return FindSweep(*db_, SweepId(number));
  });
}

absl::StatusOr<SweepRecord> RunStore::GetSweep(absl::string_view sweep_id) {
  return Transaction([&] { return FindSweep(*db_, sweep_id); });
}

absl::StatusOr<std::vector<SweepRecord>> RunStore::ListSweeps() {
  return Transaction([&]() -> absl::StatusOr<std::vector<SweepRecord>> {
    std::vector<int64_t> numbers;
    SQLite::Statement query(*db_, "SELECT number FROM sweeps ORDER BY number");
    while (query.executeStep()) numbers.push_back(query.getColumn(0).getInt64());
    std::vector<SweepRecord> sweeps;
    for (int64_t number : numbers) {
      DCS_ASSIGN_OR_RETURN(sweeps.emplace_back(), FindSweep(*db_, SweepId(number)));
    }
    return sweeps;
  });
}

absl::StatusOr<std::vector<RunRecord>> RunStore::ListSweepRuns(absl::string_view sweep_id) {
  return Transaction([&]() -> absl::StatusOr<std::vector<RunRecord>> {
    DCS_ASSIGN_OR_RETURN(const int64_t number, SweepNumber(sweep_id));
    DCS_RETURN_IF_ERROR(FindSweep(*db_, sweep_id).status());
    return FindRuns(*db_, "sweep = ?", number);
  });
}

absl::StatusOr<SweepRecord> RunStore::CancelSweep(absl::string_view sweep_id, absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<SweepRecord> {
    DCS_ASSIGN_OR_RETURN(const SweepRecord sweep, FindSweep(*db_, sweep_id));
    const int64_t number = *SweepNumber(sweep_id);
    std::vector<RunRecord> active = SweepRunsIn(*db_, number, RunState::kQueued);
    for (RunRecord& run : SweepRunsIn(*db_, number, RunState::kRunning)) {
      active.push_back(std::move(run));
    }
    if (active.empty()) {
      return absl::FailedPreconditionError(absl::StrCat(
          sweep_id, " is ", NameOf(kSweepStateNames, sweep.state), ": no run to cancel"));
    }
    for (const RunRecord& run : active) {
      DCS_RETURN_IF_ERROR(CancelRunRow(*db_, run, "its sweep was cancelled", now));
    }
    SQLite::Statement mark(*db_, "UPDATE sweeps SET cancelled = 1 WHERE number = ?");
    mark.bind(1, number);
    mark.exec();
    TouchSweep(*db_, number, now);
    return FindSweep(*db_, sweep_id);
  });
}

absl::StatusOr<std::pair<SweepRecord, int>> RunStore::RetrySweep(absl::string_view sweep_id,
                                                                 absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<std::pair<SweepRecord, int>> {
    DCS_RETURN_IF_ERROR(FindSweep(*db_, sweep_id).status());
    const int64_t number = *SweepNumber(sweep_id);
    const std::vector<RunRecord> failed = SweepRunsIn(*db_, number, RunState::kFailed);
    if (failed.empty()) {
      return absl::FailedPreconditionError(absl::StrCat(sweep_id, " has no failed run to retry"));
    }
    for (const RunRecord& run : failed) {
      DCS_RETURN_IF_ERROR(SetRunState(*db_, run, RunState::kQueued, "", now));
    }
    TouchSweep(*db_, number, now);
    DCS_ASSIGN_OR_RETURN(SweepRecord sweep, FindSweep(*db_, sweep_id));
    return std::make_pair(std::move(sweep), static_cast<int>(failed.size()));
  });
}

}  // namespace dcs::coordinator
