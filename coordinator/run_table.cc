// Copyright 2026 The DCS Authors.
#include "coordinator/run_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

// Grants lease (number, slot) to `holder` at `now`: next epoch, lasting `duration`. Returns the
// epoch.
int64_t Grant(SQLite::Database& db, int64_t number, int slot, absl::string_view holder,
              absl::string_view address, absl::Time now, absl::Duration duration) {
  SQLite::Statement update(db, "UPDATE leases SET epoch = epoch + 1, holder = ?, address = ?, "
                               "deadline = ?, granted_at = ? WHERE run = ? AND slot = ? "
                               "RETURNING epoch");
  update.bind(1, std::string(holder));
  update.bind(2, std::string(address));
  update.bind(3, Micros(now + duration));
  update.bind(4, Micros(now));
  update.bind(5, number);
  update.bind(6, slot);
  update.executeStep();
  return update.getColumn(0).getInt64();
}

// When no work fits a worker: FAILED_PRECONDITION if some run (of `which` state) waits for
// workers of other numerics (`column`), naming both fingerprints; nullopt otherwise.
template <typename Lease>
absl::StatusOr<std::optional<Lease>> RefuseOtherNumerics(SQLite::Database& db,
                                                         absl::string_view column,
                                                         absl::string_view which,
                                                         absl::string_view numerics) {
  SQLite::Statement query(db, absl::StrCat("SELECT number, ", column, " FROM runs WHERE ", which,
                                           " AND ", column, " != '' AND ", column,
                                           " != ? ORDER BY number LIMIT 1"));
  query.bind(1, std::string(numerics));
  if (!query.executeStep()) return std::nullopt;
  return absl::FailedPreconditionError(absl::StrCat(
      RunId(query.getColumn(0).getInt64()), " computes with \"", query.getColumn(1).getString(),
      "\"; this worker with \"", numerics, "\": a run never mixes numeric libraries"));
}

}  // namespace

absl::StatusOr<RunRecord> RunTable::SubmitRun(const RunSubmission& submission, absl::Time now) {
  if (submission.request_id.empty()) {
    return absl::InvalidArgumentError("a run submission needs a request id");
  }
  if (submission.config.empty()) return absl::InvalidArgumentError("the run config is empty");
  if (submission.n_envs < 1) {
    return absl::InvalidArgumentError(absl::StrCat("n_envs is ", submission.n_envs,
                                                   "; a run needs at least one slot"));
  }
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<RunRecord> {
    SQLite::Statement existing(db, "SELECT number FROM runs WHERE request_id = ?");
    existing.bind(1, submission.request_id);
    if (existing.executeStep()) return FindRun(db, RunId(existing.getColumn(0).getInt64()));

    const int64_t number = InsertRun(db, submission, std::nullopt, std::nullopt, now);
    return FindRun(db, RunId(number));
  });
}

absl::StatusOr<RunRecord> RunTable::GetRun(absl::string_view run_id) {
  return connection_.Transaction([&](SQLite::Database& db) { return FindRun(db, run_id); });
}

absl::StatusOr<std::vector<RunRecord>> RunTable::ListRuns() {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<RunRecord>> {
        return FindRuns(db, "1");
      });
}

absl::StatusOr<RunRecord> RunTable::CancelRun(absl::string_view run_id, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<RunRecord> {
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, run_id));
    DCS_RETURN_IF_ERROR(CancelRunRow(db, run, "cancelled by a client", now));
    return FindRun(db, run_id);
  });
}

absl::StatusOr<std::vector<RunRecord>> RunTable::DeleteRuns(
    absl::Span<const std::string> run_ids) {
  if (run_ids.empty()) return absl::InvalidArgumentError("name a run to remove");
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<RunRecord>> {
        std::vector<RunRecord> removed;
        for (const std::string& run_id : run_ids) {
          DCS_ASSIGN_OR_RETURN(RunRecord run, FindRun(db, run_id));
          if (std::ranges::any_of(removed, [&](const RunRecord& r) { return r.id == run.id; })) {
            continue;
          }
          if (!run.sweep_id.empty()) {
            return absl::FailedPreconditionError(absl::StrCat(
                run.id, " belongs to ", run.sweep_id, ", whose report needs all its runs: ",
                "remove the sweep with `dcs sweeps rm ", run.sweep_id, "`"));
          }
          DCS_RETURN_IF_ERROR(
              CheckRemovable(db, run, absl::StrCat("`dcs runs cancel ", run.id, "`")));
          removed.push_back(std::move(run));
        }
        for (const RunRecord& run : removed) DeleteRunRows(db, *RunNumber(run.id));
        return removed;
      });
}

absl::StatusOr<std::vector<std::string>> RunTable::RemovedRuns(
    absl::Span<const std::string> names) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<std::string>> {
        // AUTOINCREMENT: the highest number ever given, kept after its row goes.
        SQLite::Statement highest(db, "SELECT seq FROM sqlite_sequence WHERE name = 'runs'");
        const int64_t given = highest.executeStep() ? highest.getColumn(0).getInt64() : 0;
        highest.reset();
        SQLite::Statement kept(db, "SELECT 1 FROM runs WHERE number = ?");
        std::vector<std::string> removed;
        for (const std::string& name : names) {
          const absl::StatusOr<int64_t> number = RunNumber(name);
          if (!number.ok() || *number < 1 || *number > given || RunId(*number) != name) continue;
          kept.bind(1, *number);
          if (!kept.executeStep()) removed.push_back(name);
          kept.reset();
        }
        return removed;
      });
}

absl::StatusOr<std::optional<LearnerLease>> RunTable::AcquireRun(absl::string_view holder,
                                                                 absl::string_view address,
                                                                 absl::string_view numerics,
                                                                 absl::Time now) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::optional<LearnerLease>> {
        DCS_RETURN_IF_ERROR(connection_.ExpireLapsedLeases(db, now).status());
        // Fair across sweeps: the fewest running runs of the same sweep first (a run alone has
        // none), then the oldest.
        SQLite::Statement query(db, "SELECT number FROM runs AS r WHERE state = 'queued' AND "
                                    "(learner_numerics = '' OR learner_numerics = ?) "
                                    "ORDER BY (SELECT count(*) FROM runs WHERE sweep = r.sweep "
                                    "AND state = 'running'), number LIMIT 1");
        query.bind(1, std::string(numerics));
        if (!query.executeStep()) {
          query.reset();
          return RefuseOtherNumerics<LearnerLease>(db, "learner_numerics", "state = 'queued'",
                                                   numerics);
        }
        const int64_t number = query.getColumn(0).getInt64();
        query.reset();
        DCS_ASSIGN_OR_RETURN(const RunRecord queued, FindRun(db, RunId(number)));
        DCS_RETURN_IF_ERROR(SetRunState(db, queued, RunState::kRunning, "", now));
        PinNumerics(db, "learner_numerics", number, numerics);
        FreeLeases(db, number, /*learner=*/false);
        const int64_t epoch =
            Grant(db, number, kLearnerSlot, holder, address, now, connection_.lease_duration());
        DCS_ASSIGN_OR_RETURN(RunRecord run, FindRun(db, RunId(number)));
        LearnerLease lease{.key = {.run_id = run.id, .slot = kLearnerSlot, .epoch = epoch},
                           .run = std::move(run)};
        SQLite::Statement trial(db,
                                "SELECT t.condition, t.observe FROM runs r JOIN trials t "
                                "ON t.sweep = r.sweep AND t.trial = r.trial WHERE r.number = ?");
        trial.bind(1, number);
        if (trial.executeStep()) {
          lease.condition = trial.getColumn(0).getString();
          lease.observe = trial.getColumn(1).getString();
        }
        return lease;
      });
}

absl::StatusOr<std::optional<SlotLease>> RunTable::AcquireSlot(
    absl::string_view holder, absl::string_view numerics,
    absl::Span<const LeaseKey> complete_learners, absl::Time now) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::optional<SlotLease>> {
        DCS_RETURN_IF_ERROR(connection_.ExpireLapsedLeases(db, now).status());
        SQLite::Statement query(
            db, "SELECT s.run, s.slot, l.address, l.epoch FROM leases s "
                "JOIN leases l ON l.run = s.run AND l.slot = -1 JOIN runs r ON r.number = s.run "
                "WHERE s.slot >= 0 AND s.holder = '' AND l.holder != '' AND r.state = 'running' "
                "AND (r.actor_numerics = '' OR r.actor_numerics = ?) ORDER BY s.run, s.slot");
        query.bind(1, std::string(numerics));
        while (query.executeStep()) {
          const int64_t number = query.getColumn(0).getInt64();
          const std::string run_id = RunId(number);
          const int64_t learner_epoch = query.getColumn(3).getInt64();
          const bool complete =
              std::ranges::any_of(complete_learners, [&](const LeaseKey& learner) {
                return learner.slot == kLearnerSlot && learner.epoch == learner_epoch &&
                       learner.run_id == run_id;
              });
          if (complete) continue;
          const int slot = query.getColumn(1).getInt();
          std::string learner_address = query.getColumn(2).getString();
          query.reset();
          DCS_ASSIGN_OR_RETURN(RunRecord run, FindRun(db, run_id));
          const int64_t epoch =
              Grant(db, number, slot, holder, "", now, connection_.lease_duration());
          PinNumerics(db, "actor_numerics", number, numerics);
          return SlotLease{.key = {.run_id = run.id, .slot = slot, .epoch = epoch},
                           .learner_address = std::move(learner_address),
                           .learner_epoch = learner_epoch,
                           .seed = run.submission.seed,
                           .config = std::move(run.submission.config)};
        }
        query.reset();
        return RefuseOtherNumerics<SlotLease>(db, "actor_numerics", "state = 'running'", numerics);
      });
}

absl::Status RunTable::RenewLease(const LeaseKey& key, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    SQLite::Statement update(db, "UPDATE leases SET deadline = ? WHERE run = ? AND slot = ?");
    update.bind(1, Micros(now + connection_.lease_duration()));
    update.bind(2, *RunNumber(key.run_id));
    update.bind(3, key.slot);
    update.exec();
    return absl::OkStatus();
  }, internal::Commit::kUnsynced);
}

absl::Status RunTable::ReleaseLease(const LeaseKey& key, absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    const int64_t number = *RunNumber(key.run_id);
    if (key.slot == kLearnerSlot) {
      FreeLeases(db, number, /*learner=*/true);
      DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, key.run_id));
      return SetRunState(db, run, RunState::kQueued, "", now);
    }
    SQLite::Statement update(db, "UPDATE leases SET holder = '', address = '', deadline = 0 "
                                 "WHERE run = ? AND slot = ?");
    update.bind(1, number);
    update.bind(2, key.slot);
    update.exec();
    return absl::OkStatus();
  }, internal::Commit::kUnsynced);
}

absl::Status RunTable::ReportProgress(const LeaseKey& key, const RunProgress& progress,
                                      absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    SQLite::Statement update(db,
                             "UPDATE runs SET timesteps = max(timesteps, ?), policy_version = ?, "
                             "steps_per_second = ?, recent_return = ?, avg_combined = ?, "
                             "evaluation_step = ?, updated_at = ? WHERE number = ?");
    update.bind(1, progress.timesteps);
    update.bind(2, progress.policy_version);
    update.bind(3, progress.steps_per_second);
    BindDoubleOrNull(update, 4, progress.recent_return);
    if (progress.avg_combined.has_value()) {
      update.bind(5, *progress.avg_combined);
    } else {
      update.bind(5);
    }
    if (progress.evaluation_step.has_value()) {
      update.bind(6, *progress.evaluation_step);
    } else {
      update.bind(6);
    }
    update.bind(7, Micros(now));
    update.bind(8, *RunNumber(key.run_id));
    update.exec();
    return absl::OkStatus();
  }, internal::Commit::kUnsynced);
}

absl::Status RunTable::FinishRun(const LeaseKey& key, RunState state, absl::string_view error,
                                 absl::Time now) {
  if (state != RunState::kCompleted && state != RunState::kFailed) {
    return absl::InvalidArgumentError(absl::StrCat(
        "a run finishes completed or failed, not ", NameOf(kRunStateNames, state)));
  }
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, key.run_id));
    DCS_RETURN_IF_ERROR(SetRunState(db, run, state, error, now));
    FreeLeases(db, *RunNumber(key.run_id), /*learner=*/true);
    DropEvaluationWeights(db, *RunNumber(key.run_id));
    return absl::OkStatus();
  });
}

}  // namespace dcs::coordinator
