// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEARNER_HOSTED_RUNS_H_
#define DCS_SERVICES_LEARNER_HOSTED_RUNS_H_

// The runs a learner hosts (docs/architecture.md §9). A manager thread takes runs from the
// coordinator while fewer than max_runs are hosted (AcquireRun), renews their leases
// (services/lease_renewals.h), and drops a run whose lease moved or whose run ended. Each run
// has its own thread, which loads the run (from the coordinator's latest checkpoint, if any)
// into a learner::RunHost, then steps it: after every update it reports progress, uploads the
// checkpoints that fall due (retrying until the coordinator stored them or the lease is lost),
// and at the end finishes the run. Updates of different runs thus run in parallel, each on its
// own thread with libtorch pinned to one thread per process call (learner/torch_runtime.h).
//
// A learner's own disk holds nothing: a learner that dies loses only the updates since the
// run's last checkpoint, which the next learner to take the run repeats, bit for bit.
// Evaluations are handed to the coordinator for actors (services/learner/remote_evaluation.h).
//
// Thread-safe. The destructor stops everything.

#include <prometheus/registry.h>

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "learner/run_host.h"
#include "run/run_checkpoint.h"
#include "services/learner/run_metrics.h"

namespace dcs::services {

struct HostedRunsOptions {
  std::string coordinator_address;
  std::string numerics;  // the numeric libraries' fingerprint (learner/torch_runtime.h)
  int max_runs = 1;
  // How long the coordinator may hold a request for a run while none is queued (a long poll),
  // and so how often a learner with room asks; half of it for an evaluation's results.
  absl::Duration poll_interval = absl::Milliseconds(200);
  absl::Duration rpc_timeout = absl::Seconds(10);
  absl::Duration transfer_timeout = absl::Minutes(2);  // a checkpoint's stream
};

class HostedRuns {
 public:
  // Borrows `metrics`, which must outlive this.
  HostedRuns(HostedRunsOptions options, prometheus::Registry& metrics);
  ~HostedRuns();
  HostedRuns(const HostedRuns&) = delete;
  HostedRuns& operator=(const HostedRuns&) = delete;

  // Starts taking runs, for a LearnerService that actors reach at `address`.
  void Start(std::string address);

  // The host of run `run_id` for the actors of its learner lease `learner_epoch`, waiting up to
  // `wait` while the run loads. NOT_FOUND if this learner does not host the run;
  // FAILED_PRECONDITION for another epoch of its lease; UNAVAILABLE if it still loads.
  absl::StatusOr<std::shared_ptr<learner::RunHost>> Find(
      const std::string& run_id, int64_t learner_epoch,
      absl::Duration wait = absl::ZeroDuration());

  // Stops taking runs and stops every run (its lease lapses, to go to another learner).
  void Stop();

  // Calls `changed(run_id)` whenever what Find and the run's host answer for a run may have
  // changed (the run loaded, a policy was published, its host stopped): for a service that
  // waits for work without holding a thread in Find or GetSlotWork. From any thread, while
  // holding a lock of this object's own (so `changed` must not call into it); null to stop,
  // which returns once no call of the last `changed` is running.
  void OnRunChanged(std::function<void(const std::string& run_id)> changed);

 private:
  struct Run;

  void Manage();
  // Takes a run (waiting up to a poll interval at the coordinator for one) and starts its
  // thread; false if it got none.
  bool AcquireRun();
  void Train(Run& run);
  // Loads the run's host. On an error the run is finished as failed.
  absl::StatusOr<std::shared_ptr<learner::RunHost>> Load(Run& run);
  // Makes `attempt`, a call to the coordinator, until it succeeds, the run's lease is lost
  // (FAILED_PRECONDITION, NOT_FOUND), or the learner stops.
  template <typename Attempt>
  absl::Status Retry(Run& run, Attempt attempt);
  // The run's latest checkpoint from the coordinator; nullopt if it has none yet.
  absl::StatusOr<std::optional<run::Checkpoint>> FetchCheckpoint(Run& run);
  // Sends `checkpoint` with the part of `log`, the run's evaluation log as of it, that the
  // coordinator has not stored yet; the coordinator stores both before answering.
  absl::Status PutCheckpoint(Run& run, const run::Checkpoint& checkpoint,
                             const v1::EvaluationLog& log);
  // Tells the coordinator the run ended in `state`: completed, or failed with `error`.
  void Finish(Run& run, v1::RunState state, const std::string& error);
  // Tells the OnRunChanged listener, if any.
  void Changed(const std::string& run_id);

  const HostedRunsOptions options_;
  // Shared with the hosts' evaluators (services/learner/remote_evaluation.h).
  const std::shared_ptr<v1::CoordinatorService::Stub> coordinator_;
  const std::shared_ptr<RunMetrics::Families> metric_families_;
  std::string address_;  // set by Start, before the manager thread starts

  absl::Notification stopping_;
  absl::Mutex mu_;
  // By run id and learner lease epoch: a run lost may be granted again before its old thread
  // is reaped.
  std::map<std::pair<std::string, int64_t>, std::shared_ptr<Run>> runs_ ABSL_GUARDED_BY(mu_);
  absl::Duration lease_duration_ ABSL_GUARDED_BY(mu_);  // the coordinator's, as it last said

  absl::Mutex changed_mu_;  // never held while taking mu_ or a run's mu
  std::function<void(const std::string& run_id)> changed_ ABSL_GUARDED_BY(changed_mu_);

  std::thread manager_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEARNER_HOSTED_RUNS_H_
