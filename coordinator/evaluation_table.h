// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_EVALUATION_TABLE_H_
#define DCS_COORDINATOR_EVALUATION_TABLE_H_

// The store's evaluations (coordinator/store.h holds the whole store): policies handed over
// for evaluation, as jobs for actors, and their results.
//
// A run's learner hands over its policy's evaluation (docs/architecture.md §9); one job per
// evaluation context goes to actors. Jobs are leased as a run's leases are
// (coordinator/run_table.h: a deadline, an epoch raised by each grant, lapsed jobs back to the
// queue); their results are kept, the policy they evaluated is dropped once every context is in. A
// grid evaluation (a client's, `dcs eval --on-actors`) is an evaluation of its own kind: one job
// per cell of its grid, under a negative policy version.
//
// Thread-safe: every call is one transaction on the store's one connection; it returns after
// the transaction committed. Times are passed in (tests drive the clock).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "absl/types/span.h"
#include "coordinator/run_table.h"
#include "run/worker_reports.h"

namespace dcs::coordinator {

// An actor's returns in one evaluation context, in the words the actors use too.
using run::ContextReturns;

// An evaluation a run's learner hands over: the policy of `policy_version`, evaluated at
// training step `step` on each of the run's `contexts` evaluation contexts, with `episodes`
// episodes each.
struct EvaluationRequest {
  int64_t policy_version = 0;
  int64_t step = 0;
  int contexts = 0;
  int episodes = 0;
  std::string weights;  // the policy, serialised by the caller; opaque here
};

// A grid evaluation a client hands over (`dcs eval --on-actors`): a policy of run `run_id`
// evaluated in each of `cells` cells of a grid of contexts, `episodes` episodes each.
struct GridEvaluationRequest {
  std::string request_id;  // client-chosen; a repeated id returns the evaluation it created
  std::string run_id;
  int cells = 0;
  int episodes = 0;
  std::string grid;     // the grid's axes and seed, serialised by the caller; opaque here
  std::string weights;  // the policy, serialised by the caller; opaque here
};

// Names one evaluation job as its holder was granted it.
struct EvaluationJobKey {
  std::string run_id;
  int64_t policy_version = 0;
  int context = 0;
  int64_t epoch = 0;
};

// Jobs of one evaluation leased to an actor together, with what it needs to run them.
struct EvaluationGrant {
  std::vector<EvaluationJobKey> jobs;  // of one run and policy version, by context
  std::string config;                  // the run's, its seed applied
  int episodes = 0;
  std::string weights;
  // For cells of a grid evaluation, its grid (GridEvaluationRequest::grid: the jobs' contexts
  // are its cells); empty for a run's own evaluation.
  std::string grid;
};

// A job's result as its holder delivers it.
struct JobResult {
  EvaluationJobKey job;
  ContextReturns result;
};

// How an evaluation stands: `results` holds every context's, in context order, once `done`
// reaches `contexts`, and nothing before.
struct EvaluationProgress {
  int contexts = 0;
  int done = 0;
  std::vector<ContextReturns> results;
};

class EvaluationTable {
 public:
  EvaluationTable(const EvaluationTable&) = delete;
  EvaluationTable& operator=(const EvaluationTable&) = delete;

  // The learner holding `key` hands over an evaluation. Idempotent: the same policy version
  // again is accepted as it stands. INVALID_ARGUMENT for no contexts, episodes or weights, for
  // a negative policy version (those key grid evaluations), or for a version submitted before
  // with other contexts or episodes; otherwise errors as RunTable::RenewLease.
  absl::Status SubmitEvaluation(const LeaseKey& key, const EvaluationRequest& evaluation,
                                absl::Time now);

  // A client hands over a grid evaluation of a run in any state, ended ones included: one job
  // per cell, whose results GetEvaluation gives under the returned key (a negative policy
  // version of the run, the next one free). Idempotent: a request id seen before returns the
  // key it was given, the request as it stands. INVALID_ARGUMENT for no request id, cells,
  // episodes, grid or weights, or a request id used before for another run; NOT_FOUND for an
  // unknown run. The policy is dropped once every cell is in; the results are kept.
  absl::StatusOr<int64_t> SubmitGridEvaluation(const GridEvaluationRequest& evaluation,
                                               absl::Time now);

  // Free jobs of the oldest evaluation with any that an actor with `numerics` may run (of a
  // running run; or, if `grid_cells`, the actor evaluates them, cells of a grid evaluation of
  // any run), leased to `holder` until now + lease_duration: at most `max_jobs`, and at most
  // this actor's share of them among `actors` actors (at least 1), rounded up, so that one
  // evaluation spreads over the cluster while each actor takes its part in one call. A run's
  // own evaluations go before grid evaluations, however old: a learner may be waiting for its
  // result, and they are a few jobs each; a grid waits for an actor at most as long as the
  // runs' evaluations keep every actor busy. nullopt if there is none. Not synced (store.h):
  // a job's epoch fences no one out (any holder it was granted to may deliver its result, the
  // same whoever computes it), so a grant the machine's crash loses is granted again, harmlessly.
  absl::StatusOr<std::optional<EvaluationGrant>> AcquireEvaluationJobs(absl::string_view holder,
                                                                       absl::string_view numerics,
                                                                       int max_jobs, int actors,
                                                                       bool grid_cells,
                                                                       absl::Time now);

  // The holder delivers jobs' results, all of them or (on an error) none; returns, for each,
  // whether it was delivered before (a retry). Any holder the job was granted to may deliver
  // it, also after its lease lapsed and the job went to another: its result is the same whoever
  // computes it, and the first delivery is kept. Errors name the job: NOT_FOUND for an unknown
  // one; FAILED_PRECONDITION for an epoch it was never granted at; INVALID_ARGUMENT for a
  // number of returns other than the evaluation's episodes or a non-finite one. Not synced
  // (store.h): results the machine's crash loses are computed again, to the same returns, once
  // their jobs' leases lapse.
  absl::StatusOr<std::vector<bool>> ReportEvaluationJobs(absl::Span<const JobResult> results);

  // Where the evaluation of `policy_version` of `run_id` stands (a grid evaluation's: its
  // key; its contexts are the cells). NOT_FOUND if it was never submitted.
  absl::StatusOr<EvaluationProgress> GetEvaluation(absl::string_view run_id,
                                                   int64_t policy_version);

 private:
  friend class Store;
  explicit EvaluationTable(internal::StoreConnection& connection) : connection_(connection) {}

  internal::StoreConnection& connection_;  // the Store's, which owns this table too
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_EVALUATION_TABLE_H_
