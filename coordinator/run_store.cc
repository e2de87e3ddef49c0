// Copyright 2026 The DCS Authors.
#include "coordinator/run_store.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>
#include <fcntl.h>
#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "coordinator/store_rows.h"
#include "coordinator/store_schema.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

std::string LeaseName(const LeaseKey& key) {
  return key.slot == kLearnerSlot ? absl::StrCat("the learner lease of ", key.run_id)
                                  : absl::StrCat("the lease of slot ", key.slot, " of ",
                                                 key.run_id);
}

// OK if `key` names the lease as it is held now: same epoch, still held, run not ended.
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

// Grants lease (number, slot) to `holder`: next epoch, deadline from now. Returns the epoch.
int64_t Grant(SQLite::Database& db, int64_t number, int slot, absl::string_view holder,
              absl::string_view address, absl::Time deadline) {
  SQLite::Statement update(db, "UPDATE leases SET epoch = epoch + 1, holder = ?, address = ?, "
                               "deadline = ? WHERE run = ? AND slot = ? RETURNING epoch");
  update.bind(1, std::string(holder));
  update.bind(2, std::string(address));
  update.bind(3, Micros(deadline));
  update.bind(4, number);
  update.bind(5, slot);
  update.executeStep();
  return update.getColumn(0).getInt64();
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

std::string JobName(const EvaluationJobKey& key) {
  return absl::StrCat("the evaluation job of context ", key.context, " of policy version ",
                      key.policy_version, " of ", key.run_id);
}

// Records `result` for the job `key` names, in the caller's transaction; returns true if it was
// recorded before. Errors as RunStore::ReportEvaluationJobs.
absl::StatusOr<bool> RecordJobResult(SQLite::Database& db, const EvaluationJobKey& key,
                                     const ContextReturns& result) {
  DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(key.run_id));
  SQLite::Statement query(db, "SELECT j.epoch, j.done, e.episodes, e.contexts "
                              "FROM evaluation_jobs j JOIN evaluations e "
                              "ON e.run = j.run AND e.policy_version = j.policy_version "
                              "WHERE j.run = ? AND j.policy_version = ? AND j.context = ?");
  query.bind(1, number);
  query.bind(2, key.policy_version);
  query.bind(3, key.context);
  if (!query.executeStep()) {
    return absl::NotFoundError(absl::StrCat(JobName(key), " does not exist"));
  }
  const int64_t epoch = query.getColumn(0).getInt64();
  const bool done = query.getColumn(1).getInt() != 0;
  const int episodes = query.getColumn(2).getInt();
  const int contexts = query.getColumn(3).getInt();
  query.reset();
  // Any holder the job was granted to may deliver it, even after its lease lapsed and the job
  // went to another: the result is the same whoever computes it, and a job longer than a lease
  // would otherwise pass from actor to actor for ever. The first delivery is kept.
  if (key.epoch < 1 || key.epoch > epoch) {
    return absl::FailedPreconditionError(absl::StrCat(JobName(key), " was never granted at epoch ",
                                                      key.epoch, " (its latest is epoch ", epoch,
                                                      ")"));
  }
  if (done) return true;
  if (static_cast<int>(result.returns.size()) != episodes) {
    return absl::InvalidArgumentError(absl::StrCat(JobName(key), " has ", episodes,
                                                   " episodes; ", result.returns.size(),
                                                   " returns were delivered"));
  }
  SQLite::Statement insert(db, "INSERT INTO evaluation_returns (run, policy_version, "
                               "context, episode, value) VALUES (?, ?, ?, ?, ?)");
  for (int episode = 0; episode < episodes; ++episode) {
    insert.bind(1, number);
    insert.bind(2, key.policy_version);
    insert.bind(3, key.context);
    insert.bind(4, episode);
    insert.bind(5, result.returns[episode]);
    insert.exec();
    insert.reset();
  }
  SQLite::Statement finish(db, "UPDATE evaluation_jobs SET done = 1, holder = '', "
                               "deadline = 0, seconds = ? WHERE run = ? AND "
                               "policy_version = ? AND context = ?");
  finish.bind(1, result.seconds);
  finish.bind(2, number);
  finish.bind(3, key.policy_version);
  finish.bind(4, key.context);
  finish.exec();
  // Once every context is in, nothing evaluates the policy again: drop it.
  SQLite::Statement remaining(db, "SELECT count(*) FROM evaluation_jobs WHERE run = ? AND "
                                  "policy_version = ? AND done = 1");
  remaining.bind(1, number);
  remaining.bind(2, key.policy_version);
  remaining.executeStep();
  if (remaining.getColumn(0).getInt() == contexts) {
    remaining.reset();
    SQLite::Statement drop(db, "UPDATE evaluations SET weights = x'' WHERE run = ? AND "
                               "policy_version = ?");
    drop.bind(1, number);
    drop.bind(2, key.policy_version);
    drop.exec();
  }
  return false;
}

// Inserts the evaluation (run `number`, `policy_version`) and its jobs, one per context, in the
// caller's transaction.
void InsertEvaluation(SQLite::Database& db, int64_t number, int64_t policy_version, int64_t step,
                      int contexts, int episodes, const std::string& weights, absl::Time now) {
  SQLite::Statement insert(db, "INSERT INTO evaluations (run, policy_version, step, "
                               "contexts, episodes, weights, created_at) "
                               "VALUES (?, ?, ?, ?, ?, ?, ?)");
  insert.bind(1, number);
  insert.bind(2, policy_version);
  insert.bind(3, step);
  insert.bind(4, contexts);
  insert.bind(5, episodes);
  insert.bind(6, weights.data(), static_cast<int>(weights.size()));
  insert.bind(7, Micros(now));
  insert.exec();
  SQLite::Statement job(db, "INSERT INTO evaluation_jobs (run, policy_version, context) "
                            "VALUES (?, ?, ?)");
  job.bind(1, number);
  job.bind(2, policy_version);
  for (int context = 0; context < contexts; ++context) {  // reset() keeps the bindings above
    job.bind(3, context);
    job.exec();
    job.reset();
  }
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

// Pins run `number`'s numeric fingerprint of one role (`column`: learner_numerics or
// actor_numerics) to `numerics`: the workers that may take its leases of that role from now on.
void PinNumerics(SQLite::Database& db, absl::string_view column, int64_t number,
                 absl::string_view numerics) {
  SQLite::Statement pin(db, absl::StrCat("UPDATE runs SET ", column, " = ? WHERE number = ?"));
  pin.bind(1, std::string(numerics));
  pin.bind(2, number);
  pin.exec();
}

// The error of SQLite call `rc` of connection `db` writing the backup `path`: by the system's
// errno where there is one (a directory it may not write in, a full disk), else SQLite's.
absl::Status BackupError(sqlite3* db, int rc, const std::string& path) {
  if (rc == SQLITE_FULL) return FileError(ENOSPC, "cannot back the store up to", path);
  const int error = db == nullptr ? 0 : sqlite3_system_errno(db);
  if (error != 0) return FileError(error, "cannot back the store up to", path);
  return absl::InternalError(absl::StrCat("cannot back the store up to ", path, ": ",
                                          db == nullptr ? sqlite3_errstr(rc) : sqlite3_errmsg(db)));
}

struct CloseConnection {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};

}  // namespace

RunStore::RunStore(std::unique_ptr<SQLite::Database> db, RunStoreOptions options)
    : db_(std::move(db)), options_(options) {}

RunStore::~RunStore() = default;

absl::StatusOr<std::unique_ptr<RunStore>> RunStore::Open(const std::string& path,
                                                         RunStoreOptions options,
                                                         absl::Time now) {
  try {
    auto db = std::make_unique<SQLite::Database>(
        path, SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE | SQLite::OPEN_FULLMUTEX);
    db->setBusyTimeout(5000);
    db->exec("PRAGMA journal_mode = WAL");
    db->exec("PRAGMA synchronous = FULL");
    db->exec("PRAGMA foreign_keys = ON");
    DCS_RETURN_IF_ERROR(MigrateSchema(*db));
    // Holders could not renew while no coordinator ran: give them a full lease from now.
    SQLite::Statement grace(*db, "UPDATE leases SET deadline = max(deadline, ?) WHERE holder != ''");
    grace.bind(1, Micros(now + options.lease_duration));
    grace.exec();
    SQLite::Statement job_grace(
        *db, "UPDATE evaluation_jobs SET deadline = max(deadline, ?) WHERE holder != ''");
    job_grace.bind(1, Micros(now + options.lease_duration));
    job_grace.exec();
    return std::unique_ptr<RunStore>(new RunStore(std::move(db), options));
  } catch (const SQLite::Exception& e) {
    const absl::Status error = StoreError(path, e);
    return absl::Status(error.code(),
                        absl::StrCat("cannot open the coordinator database: ", error.message()));
  }
}

absl::StatusOr<RunRecord> RunStore::SubmitRun(const RunSubmission& submission, absl::Time now) {
  if (submission.request_id.empty()) {
    return absl::InvalidArgumentError("a run submission needs a request id");
  }
  if (submission.config.empty()) return absl::InvalidArgumentError("the run config is empty");
  if (submission.n_envs < 1) {
    return absl::InvalidArgumentError(absl::StrCat("n_envs is ", submission.n_envs,
                                                   "; a run needs at least one slot"));
  }
  return Transaction([&]() -> absl::StatusOr<RunRecord> {
    SQLite::Statement existing(*db_, "SELECT number FROM runs WHERE request_id = ?");
    existing.bind(1, submission.request_id);
    if (existing.executeStep()) return FindRun(*db_, RunId(existing.getColumn(0).getInt64()));

    const int64_t number = InsertRun(*db_, submission, std::nullopt, std::nullopt, now);
    return FindRun(*db_, RunId(number));
  });
}

absl::StatusOr<RunRecord> RunStore::GetRun(absl::string_view run_id) {
  return Transaction([&] { return FindRun(*db_, run_id); });
}

absl::StatusOr<std::vector<RunRecord>> RunStore::ListRuns() {
  return Transaction([&]() -> absl::StatusOr<std::vector<RunRecord>> {
    return FindRuns(*db_, "1");
  });
}

absl::StatusOr<RunRecord> RunStore::CancelRun(absl::string_view run_id, absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<RunRecord> {
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(*db_, run_id));
    DCS_RETURN_IF_ERROR(CancelRunRow(*db_, run, "cancelled by a client", now));
    return FindRun(*db_, run_id);
  });
}

absl::StatusOr<std::optional<LearnerLease>> RunStore::AcquireRun(absl::string_view holder,
                                                                 absl::string_view address,
                                                                 absl::string_view numerics,
                                                                 absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<std::optional<LearnerLease>> {
    DCS_RETURN_IF_ERROR(ExpireLapsedLeases(now));
    // Fair across sweeps: the fewest running runs of the same sweep first (a run alone has
    // none), then the oldest.
    SQLite::Statement query(*db_, "SELECT number FROM runs AS r WHERE state = 'queued' AND "
                                  "(learner_numerics = '' OR learner_numerics = ?) "
                                  "ORDER BY (SELECT count(*) FROM runs WHERE sweep = r.sweep "
                                  "AND state = 'running'), number LIMIT 1");
    query.bind(1, std::string(numerics));
    if (!query.executeStep()) {
      query.reset();
      return RefuseOtherNumerics<LearnerLease>(*db_, "learner_numerics", "state = 'queued'", numerics);
    }
    const int64_t number = query.getColumn(0).getInt64();
    query.reset();
    DCS_ASSIGN_OR_RETURN(const RunRecord queued, FindRun(*db_, RunId(number)));
    DCS_RETURN_IF_ERROR(SetRunState(*db_, queued, RunState::kRunning, "", now));
    PinNumerics(*db_, "learner_numerics", number, numerics);
    FreeLeases(*db_, number, /*learner=*/false);
    const int64_t epoch =
        Grant(*db_, number, kLearnerSlot, holder, address, now + options_.lease_duration);
    DCS_ASSIGN_OR_RETURN(RunRecord run, FindRun(*db_, RunId(number)));
    LearnerLease lease{.key = {.run_id = run.id, .slot = kLearnerSlot, .epoch = epoch},
                       .run = std::move(run)};
    SQLite::Statement trial(*db_, "SELECT t.condition, t.observe FROM runs r JOIN trials t "
                                  "ON t.sweep = r.sweep AND t.trial = r.trial WHERE r.number = ?");
    trial.bind(1, number);
    if (trial.executeStep()) {
      lease.condition = trial.getColumn(0).getString();
      lease.observe = trial.getColumn(1).getString();
    }
    return lease;
  });
}

absl::StatusOr<std::optional<SlotLease>> RunStore::AcquireSlot(
    absl::string_view holder, absl::string_view numerics,
    absl::Span<const LeaseKey> complete_learners, absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<std::optional<SlotLease>> {
    DCS_RETURN_IF_ERROR(ExpireLapsedLeases(now));
    SQLite::Statement query(
        *db_,
        "SELECT s.run, s.slot, l.address, l.epoch FROM leases s "
        "JOIN leases l ON l.run = s.run AND l.slot = -1 JOIN runs r ON r.number = s.run "
        "WHERE s.slot >= 0 AND s.holder = '' AND l.holder != '' AND r.state = 'running' "
        "AND (r.actor_numerics = '' OR r.actor_numerics = ?) ORDER BY s.run, s.slot");
    query.bind(1, std::string(numerics));
    while (query.executeStep()) {
      const int64_t number = query.getColumn(0).getInt64();
      const std::string run_id = RunId(number);
      const int64_t learner_epoch = query.getColumn(3).getInt64();
      const bool complete = std::ranges::any_of(complete_learners, [&](const LeaseKey& learner) {
        return learner.slot == kLearnerSlot && learner.epoch == learner_epoch &&
               learner.run_id == run_id;
      });
      if (complete) continue;
      const int slot = query.getColumn(1).getInt();
      std::string learner_address = query.getColumn(2).getString();
      query.reset();
      DCS_ASSIGN_OR_RETURN(RunRecord run, FindRun(*db_, run_id));
      const int64_t epoch = Grant(*db_, number, slot, holder, "", now + options_.lease_duration);
      PinNumerics(*db_, "actor_numerics", number, numerics);
      return SlotLease{.key = {.run_id = run.id, .slot = slot, .epoch = epoch},
                       .learner_address = std::move(learner_address),
                       .learner_epoch = learner_epoch,
                       .seed = run.submission.seed,
                       .config = std::move(run.submission.config)};
    }
    query.reset();
    return RefuseOtherNumerics<SlotLease>(*db_, "actor_numerics", "state = 'running'", numerics);
  });
}

absl::Status RunStore::RenewLease(const LeaseKey& key, absl::Time now) {
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    SQLite::Statement update(*db_, "UPDATE leases SET deadline = ? WHERE run = ? AND slot = ?");
    update.bind(1, Micros(now + options_.lease_duration));
    update.bind(2, *RunNumber(key.run_id));
    update.bind(3, key.slot);
    update.exec();
    return absl::OkStatus();
  });
}

absl::Status RunStore::ReleaseLease(const LeaseKey& key, absl::Time now) {
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    const int64_t number = *RunNumber(key.run_id);
    if (key.slot == kLearnerSlot) {
      FreeLeases(*db_, number, /*learner=*/true);
      DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(*db_, key.run_id));
      return SetRunState(*db_, run, RunState::kQueued, "", now);
    }
    SQLite::Statement update(*db_, "UPDATE leases SET holder = '', address = '', deadline = 0 "
                                   "WHERE run = ? AND slot = ?");
    update.bind(1, number);
    update.bind(2, key.slot);
    update.exec();
    return absl::OkStatus();
  });
}

absl::Status RunStore::SubmitEvaluation(const LeaseKey& key,
                                        const EvaluationRequest& evaluation, absl::Time now) {
  if (evaluation.contexts < 1 || evaluation.episodes < 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        "an evaluation needs contexts and episodes; got ", evaluation.contexts, " contexts of ",
        evaluation.episodes, " episodes"));
  }
  if (evaluation.weights.empty()) {
    return absl::InvalidArgumentError("an evaluation needs the policy's weights");
  }
  if (evaluation.policy_version < 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "policy version ", evaluation.policy_version,
        " is negative; negative versions key grid evaluations"));
  }
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    const int64_t number = *RunNumber(key.run_id);
    SQLite::Statement existing(*db_, "SELECT contexts, episodes FROM evaluations "
                                     "WHERE run = ? AND policy_version = ?");
    existing.bind(1, number);
    existing.bind(2, evaluation.policy_version);
    if (existing.executeStep()) {
      if (existing.getColumn(0).getInt() != evaluation.contexts ||
          existing.getColumn(1).getInt() != evaluation.episodes) {
        return absl::InvalidArgumentError(absl::StrCat(
            "policy version ", evaluation.policy_version, " of ", key.run_id,
            " was submitted for evaluation with ", existing.getColumn(0).getInt(),
            " contexts of ", existing.getColumn(1).getInt(), " episodes, now with ",
            evaluation.contexts, " of ", evaluation.episodes));
      }
      return absl::OkStatus();  // a retry, or a learner repeating it after a resume
    }
    existing.reset();
    InsertEvaluation(*db_, number, evaluation.policy_version, evaluation.step,
                     evaluation.contexts, evaluation.episodes, evaluation.weights, now);
    return absl::OkStatus();
  });
}

absl::StatusOr<int64_t> RunStore::SubmitGridEvaluation(const GridEvaluationRequest& evaluation,
                                                       absl::Time now) {
  if (evaluation.request_id.empty()) {
    return absl::InvalidArgumentError("a grid evaluation needs a request id");
  }
  if (evaluation.cells < 1 || evaluation.episodes < 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        "a grid evaluation needs cells and episodes; got ", evaluation.cells, " cells of ",
        evaluation.episodes, " episodes"));
  }
  if (evaluation.grid.empty() || evaluation.weights.empty()) {
    return absl::InvalidArgumentError("a grid evaluation needs its grid and the policy's weights");
  }
  return Transaction([&]() -> absl::StatusOr<int64_t> {
    SQLite::Statement existing(*db_, "SELECT run, policy_version FROM grid_evaluations "
                                     "WHERE request_id = ?");
    existing.bind(1, evaluation.request_id);
    if (existing.executeStep()) {  // a retry
      const std::string run_id = RunId(existing.getColumn(0).getInt64());
      if (run_id != evaluation.run_id) {
        return absl::InvalidArgumentError(absl::StrCat("request id ", evaluation.request_id,
                                                       " made a grid evaluation of ", run_id,
                                                       ", not of ", evaluation.run_id));
      }
      return existing.getColumn(1).getInt64();
    }
    existing.reset();
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(*db_, evaluation.run_id));
    const int64_t number = *RunNumber(run.id);
    SQLite::Statement next(*db_, "SELECT min(0, ifnull(min(policy_version), 0)) - 1 "
                                 "FROM evaluations WHERE run = ?");
    next.bind(1, number);
    next.executeStep();
    const int64_t key = next.getColumn(0).getInt64();
    next.reset();
    InsertEvaluation(*db_, number, key, /*step=*/0, evaluation.cells, evaluation.episodes,
                     evaluation.weights, now);
    SQLite::Statement grid(*db_, "INSERT INTO grid_evaluations (run, policy_version, "
                                 "request_id, grid) VALUES (?, ?, ?, ?)");
    grid.bind(1, number);
    grid.bind(2, key);
    grid.bind(3, evaluation.request_id);
    grid.bind(4, evaluation.grid.data(), static_cast<int>(evaluation.grid.size()));
    grid.exec();
    return key;
  });
}

absl::StatusOr<std::optional<EvaluationGrant>> RunStore::AcquireEvaluationJobs(
    absl::string_view holder, absl::string_view numerics, int max_jobs, int actors,
    bool grid_cells, absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<std::optional<EvaluationGrant>> {
    DCS_RETURN_IF_ERROR(ExpireLapsedLeases(now));
    // The runs' own evaluations first, then grid evaluations (g.run set); first in, first out
    // within each: an evaluation waits behind those handed over before it (a grid's key counts
    // down from -1: the older, the nearer 0).
    SQLite::Statement oldest(
        *db_,
        "SELECT j.run, j.policy_version, e.episodes, e.weights, r.config, "
        "ifnull(g.grid, x'') FROM evaluation_jobs j "
        "JOIN evaluations e ON e.run = j.run AND e.policy_version = j.policy_version "
        "JOIN runs r ON r.number = j.run "
        "LEFT JOIN grid_evaluations g ON g.run = j.run AND g.policy_version = j.policy_version "
        "WHERE j.done = 0 AND j.holder = '' "
        "AND ((g.run IS NULL AND r.state = 'running') OR (g.run IS NOT NULL AND ?)) "
        "AND (r.actor_numerics = '' OR r.actor_numerics = ?) "
        "ORDER BY g.run IS NOT NULL, e.created_at, j.run, abs(j.policy_version) LIMIT 1");
    oldest.bind(1, grid_cells ? 1 : 0);
    oldest.bind(2, std::string(numerics));
    if (!oldest.executeStep()) return std::nullopt;
    const int64_t number = oldest.getColumn(0).getInt64();
    const int64_t policy_version = oldest.getColumn(1).getInt64();
    EvaluationGrant grant{.config = oldest.getColumn(4).getString(),
                          .episodes = oldest.getColumn(2).getInt(),
                          .weights = oldest.getColumn(3).getString(),
                          .grid = oldest.getColumn(5).getString()};
    oldest.reset();
    SQLite::Statement free(*db_, "SELECT context FROM evaluation_jobs WHERE run = ? AND "
                                 "policy_version = ? AND done = 0 AND holder = '' "
                                 "ORDER BY context");
    free.bind(1, number);
    free.bind(2, policy_version);
    std::vector<int> contexts;
    while (free.executeStep()) contexts.push_back(free.getColumn(0).getInt());
    const size_t sharers = static_cast<size_t>(std::max(actors, 1));
    const size_t share = (contexts.size() + sharers - 1) / sharers;
    contexts.resize(std::min({contexts.size(), share, static_cast<size_t>(std::max(max_jobs, 1))}));
    SQLite::Statement lease(*db_, "UPDATE evaluation_jobs SET epoch = epoch + 1, holder = ?, "
                                  "deadline = ? WHERE run = ? AND policy_version = ? AND "
                                  "context = ? RETURNING epoch");
    lease.bind(1, std::string(holder));
    lease.bind(2, Micros(now + options_.lease_duration));
    lease.bind(3, number);
    lease.bind(4, policy_version);
    for (const int context : contexts) {  // reset() keeps the bindings above
      lease.bind(5, context);
      lease.executeStep();
      grant.jobs.push_back({.run_id = RunId(number),
                            .policy_version = policy_version,
                            .context = context,
                            .epoch = lease.getColumn(0).getInt64()});
      lease.reset();
    }
    PinNumerics(*db_, "actor_numerics", number, numerics);
    return grant;
  });
}

absl::StatusOr<std::vector<bool>> RunStore::ReportEvaluationJobs(
    absl::Span<const JobResult> results) {
  for (const auto& [key, result] : results) {
    for (size_t episode = 0; episode < result.returns.size(); ++episode) {
      if (!std::isfinite(result.returns[episode])) {
        return absl::InvalidArgumentError(absl::StrCat("the return of episode ", episode, " of ",
                                                       JobName(key), " is ",
                                                       result.returns[episode],
                                                       "; returns must be finite"));
      }
    }
  }
  return Transaction([&]() -> absl::StatusOr<std::vector<bool>> {
    std::vector<bool> delivered_before;
    for (const auto& [key, result] : results) {
      DCS_ASSIGN_OR_RETURN(const bool duplicate, RecordJobResult(*db_, key, result));
      delivered_before.push_back(duplicate);
    }
    return delivered_before;
  });
}

absl::StatusOr<EvaluationProgress> RunStore::GetEvaluation(absl::string_view run_id,
                                                           int64_t policy_version) {
  return Transaction([&]() -> absl::StatusOr<EvaluationProgress> {
    DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(run_id));
    SQLite::Statement query(*db_, "SELECT e.contexts, (SELECT count(*) FROM evaluation_jobs j "
                                  "WHERE j.run = e.run AND j.policy_version = e.policy_version "
                                  "AND j.done = 1) FROM evaluations e "
                                  "WHERE e.run = ? AND e.policy_version = ?");
    query.bind(1, number);
    query.bind(2, policy_version);
    if (!query.executeStep()) {
      return absl::NotFoundError(absl::StrCat("policy version ", policy_version, " of ", run_id,
                                              " was not submitted for evaluation"));
    }
    EvaluationProgress progress{.contexts = query.getColumn(0).getInt(),
                                .done = query.getColumn(1).getInt()};
    query.reset();
    // SubmitEvaluation stores at least one context and jobs numbered below their count: other
    // numbers mean a damaged file, not to be indexed with.
    auto corrupt = [&](absl::string_view what, int64_t value) {
      return CorruptStore(db_->getFilename(),
                          absl::StrCat("the evaluation of policy version ", policy_version, " of ",
                                       run_id, " has ", what, " ", value));
    };
    if (progress.contexts < 1) return corrupt("contexts:", progress.contexts);
    if (progress.done < progress.contexts) return progress;
    progress.results.resize(progress.contexts);
    auto context_of = [&](const SQLite::Column& column,
                          absl::string_view what) -> absl::StatusOr<size_t> {
      const int64_t context = column.getInt64();
      if (context < 0 || context >= progress.contexts) return corrupt(what, context);
      return static_cast<size_t>(context);
    };
    SQLite::Statement seconds(*db_, "SELECT context, seconds FROM evaluation_jobs "
                                    "WHERE run = ? AND policy_version = ?");
    seconds.bind(1, number);
    seconds.bind(2, policy_version);
    while (seconds.executeStep()) {
      DCS_ASSIGN_OR_RETURN(const size_t context,
                           context_of(seconds.getColumn(0), "a job of context"));
      progress.results[context].seconds = seconds.getColumn(1).getDouble();
    }
    SQLite::Statement returns(*db_, "SELECT context, value FROM evaluation_returns "
                                    "WHERE run = ? AND policy_version = ? "
                                    "ORDER BY context, episode");
    returns.bind(1, number);
    returns.bind(2, policy_version);
    while (returns.executeStep()) {
      DCS_ASSIGN_OR_RETURN(const size_t context,
                           context_of(returns.getColumn(0), "returns of context"));
      progress.results[context].returns.push_back(returns.getColumn(1).getDouble());
    }
    return progress;
  });
}

absl::StatusOr<int> RunStore::ExpireLeases(absl::Time now) {
  return Transaction([&]() -> absl::StatusOr<int> {
    DCS_RETURN_IF_ERROR(ExpireLapsedLeases(now));
    return static_cast<int>(leases_lapsing_);
  });
}

int64_t RunStore::LeasesLapsed() {
  absl::MutexLock lock(&mu_);
  return leases_lapsed_;
}

absl::Status RunStore::ExpireLapsedLeases(absl::Time now) {
  DCS_ASSIGN_OR_RETURN(const int lapsed, ExpireLapsed(*db_, now));
  leases_lapsing_ += lapsed;
  return absl::OkStatus();
}

absl::Status RunStore::ReportProgress(const LeaseKey& key, const RunProgress& progress,
                                      absl::Time now) {
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    SQLite::Statement update(*db_,
                             "UPDATE runs SET timesteps = ?, policy_version = ?, "
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
  });
}

absl::Status RunStore::RecordCheckpoint(const LeaseKey& key, const CheckpointRecord& checkpoint,
                                        absl::Time now) {
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    const int64_t number = *RunNumber(key.run_id);
    SQLite::Statement insert(*db_, "INSERT OR REPLACE INTO checkpoints (run, name, timesteps, "
                                   "sha256, created_at) VALUES (?, ?, ?, ?, ?)");
    insert.bind(1, number);
    insert.bind(2, checkpoint.name);
    insert.bind(3, checkpoint.timesteps);
    insert.bind(4, checkpoint.sha256);
    insert.bind(5, Micros(now));
    insert.exec();
    SQLite::Statement update(*db_, "UPDATE runs SET checkpoint = ?, updated_at = ? "
                                   "WHERE number = ?");
    update.bind(1, checkpoint.name);
    update.bind(2, Micros(now));
    update.bind(3, number);
    update.exec();
    return absl::OkStatus();
  });
}

absl::StatusOr<std::vector<CheckpointRecord>> RunStore::ListCheckpoints(absl::string_view run_id) {
  return Transaction([&]() -> absl::StatusOr<std::vector<CheckpointRecord>> {
    DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(run_id));
    SQLite::Statement query(*db_, "SELECT name, timesteps, sha256 FROM checkpoints "
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

absl::Status RunStore::FinishRun(const LeaseKey& key, RunState state, absl::string_view error,
                                 absl::Time now) {
  if (state != RunState::kCompleted && state != RunState::kFailed) {
    return absl::InvalidArgumentError(absl::StrCat(
        "a run finishes completed or failed, not ", NameOf(kRunStateNames, state)));
  }
  return Transaction([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(*db_, key));
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(*db_, key.run_id));
    DCS_RETURN_IF_ERROR(SetRunState(*db_, run, state, error, now));
    FreeLeases(*db_, *RunNumber(key.run_id), /*learner=*/true);
    DropEvaluationWeights(*db_, *RunNumber(key.run_id));
    return absl::OkStatus();
  });
}

absl::StatusOr<StoreCounts> RunStore::Counts() {
  return Transaction([&]() -> absl::StatusOr<StoreCounts> {
    StoreCounts counts;
    for (const auto& [state, name] : kRunStateNames) {
      SQLite::Statement query(*db_, "SELECT count(*) FROM runs WHERE state = ?");
      query.bind(1, std::string(name));
      query.executeStep();
      counts.runs_by_state.emplace_back(state, query.getColumn(0).getInt64());
    }
    counts.free_learner_leases =
        db_->execAndGet("SELECT count(*) FROM runs WHERE state = 'queued'").getInt64();
    counts.free_slot_leases =
        db_->execAndGet("SELECT count(*) FROM leases s JOIN runs r ON r.number = s.run "
                        "WHERE s.slot >= 0 AND s.holder = '' AND r.state = 'running'")
            .getInt64();
    counts.free_evaluation_jobs =
        db_->execAndGet("SELECT count(*) FROM evaluation_jobs j JOIN runs r ON r.number = j.run "
                        "WHERE j.done = 0 AND j.holder = '' "
                        "AND (r.state = 'running' OR j.policy_version < 0)")
            .getInt64();
    SQLite::Statement sweeps(
        *db_,
        "SELECT r.sweep, r.state, count(*), "
        "sum(CASE WHEN r.state IN ('queued', 'running') "
        "THEN max(0, r.total_timesteps - r.timesteps) ELSE 0 END) "
        "FROM runs r JOIN sweeps s ON s.number = r.sweep WHERE s.open != 0 OR EXISTS "
        "(SELECT 1 FROM runs a WHERE a.sweep = s.number AND a.state IN ('queued', 'running')) "
        "GROUP BY r.sweep, r.state ORDER BY r.sweep");
    while (sweeps.executeStep()) {
      const std::string sweep_id = SweepId(sweeps.getColumn(0).getInt64());
      if (counts.active_sweeps.empty() || counts.active_sweeps.back().sweep_id != sweep_id) {
        ActiveSweepCounts& sweep = counts.active_sweeps.emplace_back();
        sweep.sweep_id = sweep_id;
        for (const auto& [state, name] : kRunStateNames) sweep.runs_by_state.emplace_back(state, 0);
      }
      ActiveSweepCounts& sweep = counts.active_sweeps.back();
      // The schema's CHECK keeps states to the table's names: another means a damaged file.
      DCS_ASSIGN_OR_RETURN(const RunState state,
                           StoredValue(*db_, kRunStateNames, sweeps.getColumn(1).getString(),
                                       absl::StrCat("the state of a run of ", sweep_id)));
      sweep.runs_by_state[static_cast<int>(state)].second = sweeps.getColumn(2).getInt64();
      sweep.steps_remaining += sweeps.getColumn(3).getInt64();
    }
    return counts;
  });
}

absl::StatusOr<BackupCounts> RunStore::Backup(const std::string& path) {
  const std::string temporary = absl::StrCat(path, ".tmp.", ::getpid());
  // Everything after the copy's file exists: on an error, the temporary file goes.
  auto copy_into = [&](sqlite3* copy) -> absl::StatusOr<BackupCounts> {
    // Synced as it commits: the rename that follows publishes a whole file.
    if (const int rc = sqlite3_exec(copy, "PRAGMA synchronous = FULL", nullptr, nullptr, nullptr);
        rc != SQLITE_OK) {
      return BackupError(copy, rc, path);
    }
    absl::MutexLock lock(&mu_);
    sqlite3_backup* backup = sqlite3_backup_init(copy, "main", db_->getHandle(), "main");
    if (backup == nullptr) return BackupError(copy, sqlite3_errcode(copy), path);
    // One step copies every page under one read transaction: a snapshot, since nothing else
    // writes while the lock is held.
    const int stepped = sqlite3_backup_step(backup, -1);
    const int finished = sqlite3_backup_finish(backup);
    if (stepped != SQLITE_DONE) return BackupError(copy, stepped, path);
    if (finished != SQLITE_OK) return BackupError(copy, finished, path);
    try {
      return BackupCounts{.runs = db_->execAndGet("SELECT count(*) FROM runs").getInt64(),
                          .sweeps = db_->execAndGet("SELECT count(*) FROM sweeps").getInt64(),
                          .studies = db_->execAndGet("SELECT count(*) FROM studies").getInt64()};
    } catch (const SQLite::Exception& e) {
      return StoreError(db_->getFilename(), e);
    }
  };
  // Created here, not by SQLite, whose errno after a failed open is that of its last fallback.
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return FileError(errno, "cannot back the store up to", path);
  ::close(fd);
  sqlite3* opened = nullptr;
  const int rc = sqlite3_open_v2(temporary.c_str(), &opened,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
  std::unique_ptr<sqlite3, CloseConnection> copy(opened);
  absl::StatusOr<BackupCounts> counts =
      rc == SQLITE_OK ? copy_into(copy.get()) : BackupError(copy.get(), rc, path);
  if (counts.ok()) {
    if (const int closed = sqlite3_close(copy.release()); closed != SQLITE_OK) {
      counts = BackupError(nullptr, closed, path);
    }
  }
  if (!counts.ok()) {
    copy.reset();
    ::unlink(temporary.c_str());
    return counts;
  }
  DCS_RETURN_IF_ERROR(RenameDurably(temporary, path));
  return counts;
}

}  // namespace dcs::coordinator
