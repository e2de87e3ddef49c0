// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_ACTOR_EVALUATION_WORKER_H_
#define DCS_SERVICES_ACTOR_EVALUATION_WORKER_H_

// An actor's evaluation jobs (docs/architecture.md §9). A thread takes jobs from the coordinator
// (AcquireEvaluation): a few evaluation contexts of one policy version of a run, this actor's
// share of them. It evaluates each context with that policy (actor::EvaluateContext, Eigen, as
// `dcs train` does) or, for the cells of a grid evaluation (`dcs eval --on-actors`), each cell
// (actor::EvaluateGridCell, as `dcs eval` does in its own process), and delivers their
// episodes' returns together (ReportEvaluation, retried while the coordinator is down): a
// call per share rather than two per context. It evaluates
// holding the actor's core (the mutex its slots step under), so an actor still uses one core:
// while its slots wait for their runs' updates, it evaluates.
//
// A grant's jobs are not renewed: a job that outlasts its lease goes to another actor as well,
// and whichever delivers it first is kept (EvaluationTable::ReportEvaluationJobs). So the worker asks
// for as many as the last grant's pace fits in half a lease (at most max_jobs; one at first).
//
// A job that cannot be run here (a config this build does not know, say) is logged and left
// to lapse. Thread-safe. The destructor stops the thread.

#include <prometheus/counter.h>
#include <prometheus/registry.h>

#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "absl/time/time.h"
#include "actor/context_grid.h"
#include "actor/policy_network.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "run/run_plan.h"
#include "run/run_spec.h"

namespace dcs::services {

struct EvaluationWorkerOptions {
  std::string coordinator_address;
  std::string holder;    // the actor's name in leases
  std::string numerics;  // the numeric libraries' fingerprint
  // How long the coordinator may hold a request for jobs while it has none (a long poll), and
  // so how often an idle actor asks.
  absl::Duration poll_interval = absl::Milliseconds(200);
  absl::Duration rpc_timeout = absl::Seconds(10);
  int max_jobs = 8;  // taken at once, at most
};

class EvaluationWorker {
 public:
  // Starts the thread. Borrows `metrics` and `core`, which must outlive this.
  EvaluationWorker(EvaluationWorkerOptions options, prometheus::Registry& metrics,
                   absl::Mutex& core);
  ~EvaluationWorker();
  EvaluationWorker(const EvaluationWorker&) = delete;
  EvaluationWorker& operator=(const EvaluationWorker&) = delete;

  // Stops taking jobs and joins the thread (after the job at hand).
  void Stop();

 private:
  void Work();
  // Takes jobs (waiting up to a poll interval at the coordinator for some), runs them and
  // delivers them; false if there were none.
  bool RunJobs();
  // The returns of `job`, one of `grant`'s, with the policy `weights` (a serialised
  // PolicyWeights).
  absl::StatusOr<v1::ContextReturns> Evaluate(const v1::AcquireEvaluationResponse& grant,
                                              const v1::EvaluationJob& job,
                                              absl::string_view weights);
  // The returns of `job`, a cell of `grant`'s grid, with the prepared policy.
  absl::StatusOr<v1::ContextReturns> EvaluateGridCell(const v1::AcquireEvaluationResponse& grant,
                                                      const v1::EvaluationJob& job);
  // The run and policy of `job` (and its grid's axes), made once for the consecutive jobs of an
  // evaluation.
  absl::Status Prepare(const v1::AcquireEvaluationResponse& grant, const v1::EvaluationJob& job,
                       absl::string_view weights);

  // What the jobs of one evaluation share; the worker thread's only.
  struct Prepared {
    std::string run_id;
    int64_t policy_version = -1;
    run::RunSpec spec;
    run::RunPlan plan;
    std::optional<actor::PolicyNetwork> policy;
    std::vector<actor::GridAxis> grid_axes;  // of a grid evaluation's; empty for a run's own
  };
  Prepared prepared_;
  int jobs_wanted_ = 1;  // in the next grant; the worker thread's

  const EvaluationWorkerOptions options_;
  const std::unique_ptr<v1::CoordinatorService::Stub> coordinator_;
  prometheus::Counter& jobs_;
  absl::Mutex& core_;
  absl::Notification stopping_;
  std::thread thread_;  // last: starts after everything above is initialised
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_ACTOR_EVALUATION_WORKER_H_
