// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/run_state.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

absl::StatusOr<SweepRecord> FindSweep(SQLite::Database& db, absl::string_view sweep_id) {
  DCS_ASSIGN_OR_RETURN(const int64_t number, SweepNumber(sweep_id));
  SQLite::Statement query(db, "SELECT request_id, name, spec, seeds, cancelled, created_at, "
                              "updated_at, open, (SELECT number FROM studies WHERE sweep = "
                              "sweeps.number) FROM sweeps WHERE number = ?");
  query.bind(1, number);
  if (!query.executeStep()) return absl::NotFoundError(absl::StrCat("no sweep ", sweep_id));
  SweepRecord sweep{.id = SweepId(number),
                    .request_id = query.getColumn(0).getString(),
                    .name = query.getColumn(1).getString(),
                    .spec = query.getColumn(2).getString(),
                    .seeds = query.getColumn(3).getInt(),
                    .open = query.getColumn(7).getInt() != 0,
                    .created_at = FromMicros(query.getColumn(5).getInt64()),
                    .updated_at = FromMicros(query.getColumn(6).getInt64())};
  if (!query.getColumn(8).isNull()) sweep.study_id = StudyId(query.getColumn(8).getInt64());
  const bool cancelled = query.getColumn(4).getInt() != 0;
  query.reset();

  SQLite::Statement trials(db, "SELECT condition, family, observe, study_trial, retrain "
                               "FROM trials WHERE sweep = ? ORDER BY trial");
  trials.bind(1, number);
  while (trials.executeStep()) {
    TrialRecord& trial = sweep.trials.emplace_back(
        TrialRecord{.condition = trials.getColumn(0).getString(),
                    .family = trials.getColumn(1).getString(),
                    .observe = trials.getColumn(2).getString(),
                    .retrain = trials.getColumn(4).getInt() != 0});
    if (!trials.getColumn(3).isNull()) trial.study_trial = trials.getColumn(3).getInt64();
  }
  for (const auto& [state, name] : kRunStateNames) {
    SQLite::Statement count(db, "SELECT count(*) FROM runs WHERE sweep = ? AND state = ?");
    count.bind(1, number);
    count.bind(2, std::string(name));
    count.executeStep();
    sweep.runs_by_state.emplace_back(state, count.getColumn(0).getInt64());
  }
  sweep.state = SweepStateOf(sweep.runs_by_state, cancelled, sweep.open);
  return sweep;
}

// Every sweep matching `where` (an SQL condition on the sweeps table), oldest first.
absl::StatusOr<std::vector<SweepRecord>> FindSweeps(SQLite::Database& db,
                                                    absl::string_view where) {
  std::vector<int64_t> numbers;
  SQLite::Statement query(
      db, absl::StrCat("SELECT number FROM sweeps WHERE ", where, " ORDER BY number"));
  while (query.executeStep()) numbers.push_back(query.getColumn(0).getInt64());
  std::vector<SweepRecord> sweeps;
  for (int64_t number : numbers) {
    DCS_ASSIGN_OR_RETURN(sweeps.emplace_back(), FindSweep(db, SweepId(number)));
  }
  return sweeps;
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

// Inserts trial `index` of sweep `number`.
void InsertTrial(SQLite::Database& db, int64_t number, int index, const TrialRecord& trial) {
  SQLite::Statement insert(db, "INSERT INTO trials (sweep, trial, condition, family, observe, "
                               "study_trial, retrain) VALUES (?, ?, ?, ?, ?, ?, ?)");
  insert.bind(1, number);
  insert.bind(2, index);
  insert.bind(3, trial.condition);
  insert.bind(4, trial.family);
  insert.bind(5, trial.observe);
  if (trial.study_trial.has_value()) insert.bind(6, *trial.study_trial);
  insert.bind(7, trial.retrain ? 1 : 0);
  insert.exec();
}

// INVALID_ARGUMENT naming the run unless it has a request id, a config and an env slot.
absl::Status CheckRunSubmission(const RunSubmission& run, absl::string_view what) {
  if (!run.request_id.empty() && !run.config.empty() && run.n_envs >= 1) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat(
      "run ", run.request_id, " of ", what, " needs a request id, a config and at least one env "
      "slot"));
}

}  // namespace

absl::StatusOr<SweepRecord> SweepTable::SubmitSweep(const SweepSubmission& submission,
                                                    absl::Time now) {
  if (submission.request_id.empty()) {
    return absl::InvalidArgumentError("a sweep submission needs a request id");
  }
  if (submission.trials.empty() && !submission.study.has_value()) {
    return absl::InvalidArgumentError("the sweep has no trials");
  }
  if (submission.study.has_value()) DCS_RETURN_IF_ERROR(CheckStudySubmission(*submission.study));
  if (submission.seeds < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("the sweep has ", submission.seeds, " seeds; it needs at least one"));
  }
  for (const SweepSubmission::Run& run : submission.runs) {
    if (run.trial < 0 || run.trial >= static_cast<int>(submission.trials.size())) {
      return absl::InvalidArgumentError(absl::StrCat("a run of the sweep names trial ", run.trial,
                                                     "; it has ", submission.trials.size()));
    }
    DCS_RETURN_IF_ERROR(CheckRunSubmission(run.run, absl::StrCat("trial ", run.trial)));
  }
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<SweepRecord> {
    SQLite::Statement existing(db, "SELECT number FROM sweeps WHERE request_id = ?");
    existing.bind(1, submission.request_id);
    if (existing.executeStep()) return FindSweep(db, SweepId(existing.getColumn(0).getInt64()));

    SQLite::Statement insert(db, "INSERT INTO sweeps (request_id, name, spec, seeds, open, "
                                 "created_at, updated_at) VALUES (?, ?, ?, ?, ?, ?, ?) "
                                 "RETURNING number");
    insert.bind(1, submission.request_id);
    insert.bind(2, submission.name);
    insert.bind(3, submission.spec);
    insert.bind(4, submission.seeds);
    insert.bind(5, submission.study.has_value() ? 1 : 0);
    insert.bind(6, Micros(now));
    insert.bind(7, Micros(now));
    insert.executeStep();
    const int64_t number = insert.getColumn(0).getInt64();
    insert.reset();

    for (size_t i = 0; i < submission.trials.size(); ++i) {
      InsertTrial(db, number, static_cast<int>(i), submission.trials[i]);
    }
    for (const SweepSubmission::Run& run : submission.runs) {
      InsertRun(db, run.run, number, run.trial, now);
    }
    if (submission.study.has_value()) InsertStudy(db, *submission.study, number, now);
    return FindSweep(db, SweepId(number));
  });
}

absl::StatusOr<std::vector<RunRecord>> SweepTable::AddSweepTrial(
    absl::string_view sweep_id, const TrialRecord& trial, const std::vector<RunSubmission>& runs,
    absl::Time now) {
  if (!trial.study_trial.has_value() || runs.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat("a trial added to ", sweep_id, " needs its study trial and its runs"));
  }
  for (const RunSubmission& run : runs) {
    DCS_RETURN_IF_ERROR(CheckRunSubmission(run, trial.condition));
  }
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<RunRecord>> {
        DCS_ASSIGN_OR_RETURN(const SweepRecord sweep, FindSweep(db, sweep_id));
        const int64_t number = *SweepNumber(sweep_id);
        SQLite::Statement existing(db, "SELECT trial FROM trials WHERE sweep = ? AND "
                                       "study_trial = ? AND retrain = ?");
        existing.bind(1, number);
        existing.bind(2, *trial.study_trial);
        existing.bind(3, trial.retrain ? 1 : 0);
        int index = static_cast<int>(sweep.trials.size());
        if (existing.executeStep()) {
          index = existing.getColumn(0).getInt();
        } else {
          if (!sweep.open) {
            return absl::FailedPreconditionError(
                absl::StrCat(sweep_id, " is closed: it adds no more trials"));
          }
          InsertTrial(db, number, index, trial);
          for (const RunSubmission& run : runs) InsertRun(db, run, number, index, now);
          TouchSweep(db, number, now);
        }
        return FindRuns(db, absl::StrCat("sweep = ", number, " AND trial = ?"), index);
      });
}

absl::Status SweepTable::CloseSweep(absl::string_view sweep_id, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(FindSweep(db, sweep_id).status());
    const int64_t number = *SweepNumber(sweep_id);
    SQLite::Statement close(db, "UPDATE sweeps SET open = 0 WHERE number = ?");
    close.bind(1, number);
    close.exec();
    TouchSweep(db, number, now);
    return absl::OkStatus();
  });
}

absl::StatusOr<std::vector<SweepRecord>> SweepTable::ListOpenSweeps() {
  return connection_.Transaction([&](SQLite::Database& db) { return FindSweeps(db, "open = 1"); });
}

absl::StatusOr<SweepRecord> SweepTable::GetSweep(absl::string_view sweep_id) {
  return connection_.Transaction([&](SQLite::Database& db) { return FindSweep(db, sweep_id); });
}

absl::StatusOr<std::vector<SweepRecord>> SweepTable::ListSweeps() {
  return connection_.Transaction([&](SQLite::Database& db) { return FindSweeps(db, "1"); });
}

absl::StatusOr<std::vector<RunRecord>> SweepTable::ListSweepRuns(absl::string_view sweep_id) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<RunRecord>> {
        DCS_ASSIGN_OR_RETURN(const int64_t number, SweepNumber(sweep_id));
        DCS_RETURN_IF_ERROR(FindSweep(db, sweep_id).status());
        return FindRuns(db, "sweep = ?", number);
      });
}

absl::StatusOr<SweepRecord> SweepTable::CancelSweep(absl::string_view sweep_id, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<SweepRecord> {
    DCS_ASSIGN_OR_RETURN(const SweepRecord sweep, FindSweep(db, sweep_id));
    const int64_t number = *SweepNumber(sweep_id);
    std::vector<RunRecord> active = SweepRunsIn(db, number, RunState::kQueued);
    for (RunRecord& run : SweepRunsIn(db, number, RunState::kRunning)) {
      active.push_back(std::move(run));
    }
    if (active.empty() && !sweep.open) {
      return absl::FailedPreconditionError(absl::StrCat(
          sweep_id, " is ", NameOf(kSweepStateNames, sweep.state), ": no run to cancel"));
    }
    for (const RunRecord& run : active) {
      DCS_RETURN_IF_ERROR(CancelRunRow(db, run, "its sweep was cancelled", now));
    }
    FailRunningStudyTrials(db, number, now);
    SQLite::Statement mark(db, "UPDATE sweeps SET cancelled = 1, open = 0 WHERE number = ?");
    mark.bind(1, number);
    mark.exec();
    TouchSweep(db, number, now);
    return FindSweep(db, sweep_id);
  });
}

absl::StatusOr<std::vector<RemovedSweep>> SweepTable::DeleteSweeps(
    absl::Span<const std::string> sweep_ids) {
  if (sweep_ids.empty()) return absl::InvalidArgumentError("name a sweep to remove");
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<RemovedSweep>> {
        std::vector<RemovedSweep> removed;
        for (const std::string& sweep_id : sweep_ids) {
          DCS_ASSIGN_OR_RETURN(SweepRecord sweep, FindSweep(db, sweep_id));
          if (std::ranges::any_of(removed, [&](const RemovedSweep& r) {
                return r.sweep.id == sweep.id;
              })) {
            continue;
          }
          const std::string how_to_stop = absl::StrCat("`dcs sweeps cancel ", sweep.id, "`");
          int64_t active = 0;
          for (const auto& [state, count] : sweep.runs_by_state) {
            if (!IsTerminal(state)) active += count;
          }
          if (active > 0 || sweep.open) {
            return absl::FailedPreconditionError(absl::StrCat(
                sweep.id, " is ", NameOf(kSweepStateNames, sweep.state), " (", active,
                " of its runs queued or running", sweep.open ? ", its study asking for more" : "",
                "): stop it first with ", how_to_stop));
          }
          std::vector<RunRecord> runs = FindRuns(db, "sweep = ?", *SweepNumber(sweep.id));
          for (const RunRecord& run : runs) {
            DCS_RETURN_IF_ERROR(CheckRemovable(db, run, how_to_stop));
          }
          removed.push_back({.sweep = std::move(sweep), .runs = std::move(runs)});
        }
        for (const RemovedSweep& sweep : removed) {
          for (const RunRecord& run : sweep.runs) DeleteRunRows(db, *RunNumber(run.id));
          if (!sweep.sweep.study_id.empty()) {
            DeleteStudyRows(db, *StudyNumber(sweep.sweep.study_id));
          }
          DeleteRowAndChildren(db, "sweeps", *SweepNumber(sweep.sweep.id), "sweep", {"trials"});
        }
        return removed;
      });
}

absl::StatusOr<std::pair<SweepRecord, int>> SweepTable::RetrySweep(absl::string_view sweep_id,
                                                                   absl::Time now) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::pair<SweepRecord, int>> {
        DCS_ASSIGN_OR_RETURN(const SweepRecord sweep, FindSweep(db, sweep_id));
        if (!sweep.study_id.empty()) {
          return absl::FailedPreconditionError(
              absl::StrCat(sweep_id, " drives ", sweep.study_id,
                           ", which was told its failed trials failed: "
                           "retry is for plain sweeps"));
        }
        const int64_t number = *SweepNumber(sweep_id);
        const std::vector<RunRecord> failed = SweepRunsIn(db, number, RunState::kFailed);
        if (failed.empty()) {
          return absl::FailedPreconditionError(
              absl::StrCat(sweep_id, " has no failed run to retry"));
        }
        for (const RunRecord& run : failed) {
          DCS_RETURN_IF_ERROR(SetRunState(db, run, RunState::kQueued, "", now));
        }
        TouchSweep(db, number, now);
        DCS_ASSIGN_OR_RETURN(SweepRecord retried, FindSweep(db, sweep_id));
        return std::make_pair(std::move(retried), static_cast<int>(failed.size()));
      });
}

}  // namespace dcs::coordinator
