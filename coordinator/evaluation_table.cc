// Copyright 2026 The DCS Authors.
#include "coordinator/evaluation_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

std::string JobName(const EvaluationJobKey& key) {
  return absl::StrCat("the evaluation job of context ", key.context, " of policy version ",
                      key.policy_version, " of ", key.run_id);
}

// Records `result` for the job `key` names, in the caller's transaction; returns true if it was
// recorded before. Errors as
// EvaluationTable::ReportEvaluationJobs.
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

}  // namespace

absl::Status EvaluationTable::SubmitEvaluation(const LeaseKey& key,
                                               const EvaluationRequest& evaluation,
                                               absl::Time now) {
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
  return connection_.Transaction([&](SQLite::Database& db) -> absl::Status {
    DCS_RETURN_IF_ERROR(CheckHeld(db, key));
    const int64_t number = *RunNumber(key.run_id);
    SQLite::Statement existing(db, "SELECT contexts, episodes FROM evaluations "
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
    InsertEvaluation(db, number, evaluation.policy_version, evaluation.step,
                     evaluation.contexts, evaluation.episodes, evaluation.weights, now);
    return absl::OkStatus();
  });
}

absl::StatusOr<int64_t> EvaluationTable::SubmitGridEvaluation(
    const GridEvaluationRequest& evaluation, absl::Time now) {
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
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<int64_t> {
    SQLite::Statement existing(db, "SELECT run, policy_version FROM grid_evaluations "
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
    DCS_ASSIGN_OR_RETURN(const RunRecord run, FindRun(db, evaluation.run_id));
    const int64_t number = *RunNumber(run.id);
    SQLite::Statement next(db, "SELECT min(0, ifnull(min(policy_version), 0)) - 1 "
                               "FROM evaluations WHERE run = ?");
    next.bind(1, number);
    next.executeStep();
    const int64_t key = next.getColumn(0).getInt64();
    next.reset();
    InsertEvaluation(db, number, key, /*step=*/0, evaluation.cells, evaluation.episodes,
                     evaluation.weights, now);
    SQLite::Statement grid(db, "INSERT INTO grid_evaluations (run, policy_version, "
                               "request_id, grid) VALUES (?, ?, ?, ?)");
    grid.bind(1, number);
    grid.bind(2, key);
    grid.bind(3, evaluation.request_id);
    grid.bind(4, evaluation.grid.data(), static_cast<int>(evaluation.grid.size()));
    grid.exec();
    return key;
  });
}

absl::StatusOr<std::optional<EvaluationGrant>> EvaluationTable::AcquireEvaluationJobs(
    absl::string_view holder, absl::string_view numerics, int max_jobs, int actors, bool grid_cells,
    absl::Time now) {
  return connection_.Transaction([&](SQLite::Database& db)
                                     -> absl::StatusOr<std::optional<EvaluationGrant>> {
    DCS_RETURN_IF_ERROR(connection_.ExpireLapsedLeases(db, now).status());
    // The runs' own evaluations first, then grid evaluations (g.run set); first in, first out
    // within each: an evaluation waits behind those handed over before it (a grid's key counts
    // down from -1: the older, the nearer 0).
    SQLite::Statement oldest(
        db, "SELECT j.run, j.policy_version, e.episodes, e.weights, r.config, "
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
    SQLite::Statement free(db, "SELECT context FROM evaluation_jobs WHERE run = ? AND "
                               "policy_version = ? AND done = 0 AND holder = '' "
                               "ORDER BY context");
    free.bind(1, number);
    free.bind(2, policy_version);
    std::vector<int> contexts;
    while (free.executeStep()) contexts.push_back(free.getColumn(0).getInt());
    const size_t sharers = static_cast<size_t>(std::max(actors, 1));
    const size_t share = (contexts.size() + sharers - 1) / sharers;
    contexts.resize(std::min({contexts.size(), share, static_cast<size_t>(std::max(max_jobs, 1))}));
    SQLite::Statement lease(db, "UPDATE evaluation_jobs SET epoch = epoch + 1, holder = ?, "
                                "deadline = ? WHERE run = ? AND policy_version = ? AND "
                                "context = ? RETURNING epoch");
    lease.bind(1, std::string(holder));
    lease.bind(2, Micros(now + connection_.lease_duration()));
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
    PinNumerics(db, "actor_numerics", number, numerics);
    return grant;
  }, internal::Commit::kUnsynced);
}

absl::StatusOr<std::vector<bool>> EvaluationTable::ReportEvaluationJobs(
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
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<std::vector<bool>> {
    std::vector<bool> delivered_before;
    for (const auto& [key, result] : results) {
      DCS_ASSIGN_OR_RETURN(const bool duplicate, RecordJobResult(db, key, result));
      delivered_before.push_back(duplicate);
    }
    return delivered_before;
  }, internal::Commit::kUnsynced);
}

absl::StatusOr<EvaluationProgress> EvaluationTable::GetEvaluation(absl::string_view run_id,
                                                                  int64_t policy_version) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<EvaluationProgress> {
    DCS_ASSIGN_OR_RETURN(const int64_t number, RunNumber(run_id));
    SQLite::Statement query(db, "SELECT e.contexts, (SELECT count(*) FROM evaluation_jobs j "
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
      return CorruptStore(db.getFilename(),
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
    SQLite::Statement seconds(db, "SELECT context, seconds FROM evaluation_jobs "
                                  "WHERE run = ? AND policy_version = ?");
    seconds.bind(1, number);
    seconds.bind(2, policy_version);
    while (seconds.executeStep()) {
      DCS_ASSIGN_OR_RETURN(const size_t context,
                           context_of(seconds.getColumn(0), "a job of context"));
      progress.results[context].seconds = seconds.getColumn(1).getDouble();
    }
    SQLite::Statement returns(db, "SELECT context, value FROM evaluation_returns "
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

}  // namespace dcs::coordinator
