// Copyright 2026 The DCS Authors.
#include "services/learner/hosted_runs.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/env_registry.h"
#include "run/appended_evaluation_log.h"
#include "run/run_checkpoint.h"
#include "run/run_spec_yaml.h"
#include "services/backoff.h"
#include "services/channel.h"
#include "services/finished_threads.h"
#include "services/learner/remote_evaluation.h"
#include "services/lease_renewals.h"
#include "services/log.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/time_proto.h"
#include "services/unary_call.h"

namespace dcs::services {

struct HostedRuns::Run {
  run::LeaseKey lease;
  std::string config;
  prometheus::Labels metric_labels;  // run_id, sweep_id, condition, observe
  absl::Time renewed_at;                     // the manager thread's
  // The run's first so many evaluations are in the coordinator's log: those of the checkpoint
  // the run was loaded from, then of each checkpoint stored. The run's thread's.
  int64_t evaluations_stored = 0;

  absl::Mutex mu;
  std::shared_ptr<learner::RunHost> host ABSL_GUARDED_BY(mu);  // null while loading

  std::atomic<bool> lost{false};  // the lease moved or the run ended: stop
  std::atomic<bool> done{false};  // the run's thread is about to return
  std::thread thread;

  // Stops the run: its host's Step returns CANCELLED.
  void Lose() {
    lost = true;
    absl::MutexLock lock(&mu);
    if (host != nullptr) host->Stop();
  }
};

namespace {

constexpr BackoffPolicy kRetryBackoff{.initial = absl::Milliseconds(100),
                                      .max = absl::Seconds(1)};

}  // namespace

HostedRuns::HostedRuns(HostedRunsOptions options, prometheus::Registry& metrics)
    : options_(std::move(options)),
      coordinator_(v1::CoordinatorService::NewStub(OpenChannel(options_.coordinator_address))),
      metric_families_(RunMetrics::Register(metrics)) {}

void HostedRuns::Start(std::string address) {
  address_ = std::move(address);
  manager_ = std::thread([this] { Manage(); });
}

HostedRuns::~HostedRuns() { Stop(); }

void HostedRuns::Stop() {
  if (stopping_.HasBeenNotified()) return;  // stopped already
  {
    absl::MutexLock lock(&mu_);  // wakes the manager, which waits on mu_
    stopping_.Notify();
  }
  if (manager_.joinable()) manager_.join();
  std::map<std::pair<std::string, int64_t>, std::shared_ptr<Run>> runs;
  {
    absl::MutexLock lock(&mu_);
    runs.swap(runs_);
  }
  for (auto& [key, run] : runs) {
    run->Lose();
    if (run->thread.joinable()) run->thread.join();
    // Hand the run back at once rather than let its lease lapse.
    v1::ReleaseLeaseRequest request;
    *request.mutable_lease() = LeaseToProto(run->lease);
    v1::ReleaseLeaseResponse response;
    CallUnary(*coordinator_, &v1::CoordinatorService::Stub::ReleaseLease, request, response,
              options_.rpc_timeout, "coordinator")
        .IgnoreError();
  }
}

absl::StatusOr<std::shared_ptr<learner::RunHost>> HostedRuns::Find(const std::string& run_id,
                                                                   int64_t learner_epoch,
                                                                   absl::Duration wait) {
  std::shared_ptr<Run> run;
  {
    absl::MutexLock lock(&mu_);
    auto found = runs_.find({run_id, learner_epoch});
    if (found == runs_.end()) {
      auto other = runs_.lower_bound({run_id, 0});
      if (other != runs_.end() && other->first.first == run_id) {
        return absl::FailedPreconditionError(absl::StrCat(
            run_id, " is hosted here under another learner lease epoch than ", learner_epoch));
      }
      return absl::NotFoundError(absl::StrCat("this learner does not host ", run_id));
    }
    run = found->second;
  }
  if (run->lost) {
    return absl::FailedPreconditionError(
        absl::StrCat("this learner lost ", run_id, "'s lease (epoch ", learner_epoch, ")"));
  }
  absl::MutexLock lock(&run->mu);
  auto loaded = [&run]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(run->mu) {
    return run->host != nullptr || run->lost;
  };
  run->mu.AwaitWithTimeout(absl::Condition(&loaded), wait);
  if (run->host == nullptr) {
    return absl::UnavailableError(absl::StrCat(run_id, " is still loading"));
  }
  return run->host;
}

void HostedRuns::OnRunChanged(std::function<void(const std::string& run_id)> changed) {
  absl::MutexLock lock(&changed_mu_);
  changed_ = std::move(changed);
}

void HostedRuns::Changed(const std::string& run_id) {
  absl::MutexLock lock(&changed_mu_);
  if (changed_) changed_(run_id);
}

void HostedRuns::Manage() {
  while (!stopping_.HasBeenNotified()) {
    const absl::Time round = absl::Now();
    JoinFinished(mu_, runs_);
    RenewDueLeases(*coordinator_, options_.rpc_timeout, mu_, runs_, lease_duration_,
                   [](Run& run) { run.Lose(); });
    if (AcquireRun()) continue;  // the next at once, while there is room
    // The rest of the round (the coordinator answered before it: no room here, or it could not
    // be reached, or is one that does not hold calls), or until a run ends and makes room.
    absl::MutexLock lock(&mu_);
    auto woken = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
      return stopping_.HasBeenNotified() ||
             std::any_of(runs_.begin(), runs_.end(),
                         [](const auto& entry) { return entry.second->done.load(); });
    };
    mu_.AwaitWithTimeout(absl::Condition(&woken), options_.poll_interval - (absl::Now() - round));
  }
}

bool HostedRuns::AcquireRun() {
  {
    absl::MutexLock lock(&mu_);
    if (static_cast<int>(runs_.size()) >= options_.max_runs) return false;
  }
  v1::AcquireRunRequest request;
  request.set_holder(address_);
  request.set_address(address_);
  request.set_numerics(options_.numerics);
  *request.mutable_wait() = DurationToProto(options_.poll_interval);
  v1::AcquireRunResponse response;
  const absl::Status status =
      CallUnary(*coordinator_, &v1::CoordinatorService::Stub::AcquireRun, request, response,
                options_.rpc_timeout, "coordinator");
  if (!status.ok()) {
    if (!IsTransient(status)) {
      Log(LogLevel::kWarning, "cannot take a run", {{"error", status.ToString()}});
    }
    return false;
  }
  if (!response.has_lease()) return false;
  absl::StatusOr<run::LeaseKey> lease = LeaseFromProto(response.lease());
  if (!lease.ok()) return false;
  auto run = std::make_shared<Run>();
  run->lease = *lease;
  run->config = response.config();
  run->metric_labels = {{"run_id", run->lease.run_id},
                        {"sweep_id", response.sweep_id()},
                        {"condition", response.condition()},
                        {"observe", response.observe()}};
  run->renewed_at = absl::Now();
  {
    absl::MutexLock lock(&mu_);
    lease_duration_ = DurationFromProto(response.lease_duration());
  }
  absl::MutexLock lock(&mu_);
  run->thread = std::thread([this, run] {
    Train(*run);
    absl::MutexLock done_lock(&mu_);  // wakes the manager
    run->done = true;
  });
  runs_[{run->lease.run_id, run->lease.epoch}] = std::move(run);
  return true;
}

template <typename Attempt>
absl::Status HostedRuns::Retry(Run& run, Attempt attempt) {
  const absl::Status status =
      RetryTransient(attempt, kRetryBackoff, [&](const absl::Status& failed) {
        if (run.lost || stopping_.HasBeenNotified()) return false;
        Log(LogLevel::kWarning, "coordinator call failed; retrying",
            {{"run_id", run.lease.run_id}, {"error", failed.ToString()}});
        return true;
      });
  if (IsLeaseLost(status)) run.lost = true;
  return status;
}

absl::StatusOr<std::optional<run::Checkpoint>> HostedRuns::FetchCheckpoint(Run& run) {
  v1::GetCheckpointRequest request;
  *request.mutable_lease() = LeaseToProto(run.lease);
  run::PackedCheckpoint packed;
  const absl::Status fetched = RetryTransient(
      [&] {
        bool first = true;
        return CallServerStream(*coordinator_, &v1::CoordinatorService::Stub::GetCheckpoint,
                                request, options_.transfer_timeout, "coordinator",
                                [&](const v1::CheckpointPiece& piece) {
                                  const absl::Status added =
                                      AddCheckpointPiece(piece, first, packed);
                                  first = false;
                                  return added;
                                });
      },
      kRetryBackoff,
      [&](const absl::Status&) { return !run.lost && !stopping_.HasBeenNotified(); });
  // NOT_FOUND: the run has no checkpoint yet.
  if (absl::IsNotFound(fetched)) return std::nullopt;
  if (absl::IsFailedPrecondition(fetched)) run.lost = true;
  DCS_RETURN_IF_ERROR(fetched);
  return run::UnpackCheckpoint(packed);
}

absl::Status HostedRuns::PutCheckpoint(Run& run, const run::Checkpoint& checkpoint,
                                       const v1::EvaluationLog& log) {
  const std::vector<v1::CheckpointPiece> pieces =
      CheckpointToPieces(run::PackCheckpoint(checkpoint));
  const std::string log_bytes =
      run::EvaluationLogSince(log, run.evaluations_stored).SerializeAsString();
  const std::vector<absl::string_view> log_pieces = SplitIntoPieces(log_bytes);
  std::vector<v1::PutCheckpointRequest> requests(std::max(pieces.size(), log_pieces.size()));
  *requests.front().mutable_lease() = LeaseToProto(run.lease);
  requests.front().set_evaluations_before(run.evaluations_stored);
  for (size_t i = 0; i < pieces.size(); ++i) *requests[i].mutable_checkpoint() = pieces[i];
  for (size_t i = 0; i < log_pieces.size(); ++i) {
    requests[i].set_evaluation_log(log_pieces[i].data(), log_pieces[i].size());
  }
  DCS_RETURN_IF_ERROR(Retry(run, [&] {
    v1::PutCheckpointResponse response;
    return CallClientStream(*coordinator_, &v1::CoordinatorService::Stub::PutCheckpoint, requests,
                            response, options_.transfer_timeout, "coordinator");
  }));
  run.evaluations_stored = log.evaluations_size();
  return absl::OkStatus();
}

void HostedRuns::Finish(Run& run, v1::RunState state, const std::string& error) {
  v1::FinishRunRequest request;
  *request.mutable_lease() = LeaseToProto(run.lease);
  request.set_state(state);
  request.set_error(error);
  const absl::Status status = Retry(run, [&] {
    v1::FinishRunResponse response;
    return CallUnary(*coordinator_, &v1::CoordinatorService::Stub::FinishRun, request, response,
                     options_.rpc_timeout, "coordinator");
  });
  if (!status.ok()) {
    Log(LogLevel::kWarning, "cannot finish a run",
        {{"run_id", run.lease.run_id}, {"error", status.ToString()}});
  }
}

absl::StatusOr<std::shared_ptr<learner::RunHost>> HostedRuns::Load(Run& run) {
  DCS_ASSIGN_OR_RETURN(run::RunSpec spec, run::ParseRunSpecYaml(run.config, run.lease.run_id));
  DCS_ASSIGN_OR_RETURN(const std::optional<run::Checkpoint> checkpoint, FetchCheckpoint(run));
  // The coordinator's log holds at least its evaluations (coordinator/run_files.h).
  if (checkpoint.has_value()) run.evaluations_stored = checkpoint->state.evaluations.size();
  Log(LogLevel::kInfo, "hosting a run",
      {{"run_id", run.lease.run_id}, {"epoch", std::to_string(run.lease.epoch)},
       {"checkpoint", checkpoint.has_value() ? checkpoint->name : "none"}});
  std::shared_ptr<learner::RunHost> host;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(
        host, learner::RunHost::Create<Env>(
                  spec, checkpoint.has_value() ? &*checkpoint : nullptr,
                  EvaluateOnActors(coordinator_, run.lease,
                                   {.poll_interval = options_.poll_interval / 2,
                                    .rpc_timeout = options_.rpc_timeout})));
    return absl::OkStatus();
  }));
  host->OnChange([this, run_id = run.lease.run_id] { Changed(run_id); });
  return host;
}

void HostedRuns::Train(Run& run) {
  absl::StatusOr<std::shared_ptr<learner::RunHost>> loaded = Load(run);
  if (!loaded.ok()) {
    Log(LogLevel::kError, "cannot load a run",
        {{"run_id", run.lease.run_id}, {"error", loaded.status().ToString()}});
    if (!run.lost) Finish(run, v1::RUN_STATE_FAILED, loaded.status().ToString());
    return;
  }
  {
    absl::MutexLock lock(&run.mu);
    run.host = *loaded;
    if (run.lost) run.host->Stop();
  }
  Changed(run.lease.run_id);  // its slots' work is out
  learner::RunHost& host = **loaded;
  if (host.complete()) {
    // Its checkpoint holds its end, final evaluation included (RunHost::Step stores it once
    // every evaluation is in): a learner stopped between storing it and finishing the run.
    Finish(run, v1::RUN_STATE_COMPLETED, "");
    Log(LogLevel::kInfo, "run complete: its checkpoint holds its end",
        {{"run_id", run.lease.run_id}});
    return;
  }
  RunMetrics metrics(metric_families_, run.metric_labels);
  while (true) {
    const absl::Time start = absl::Now();
    absl::StatusOr<learner::HostStep> step = host.Step();
    if (!step.ok()) {
      if (run.lost || absl::IsCancelled(step.status())) return;
      Log(LogLevel::kError, "a run failed",
          {{"run_id", run.lease.run_id}, {"error", step.status().ToString()}});
      Finish(run, v1::RUN_STATE_FAILED, step.status().ToString());
      return;
    }
    const learner::TrainingProgress& progress = step->progress;
    metrics.Update(progress, step->steps, step->episodes,
                   absl::ToDoubleSeconds(absl::Now() - start));

    v1::ReportProgressRequest report;
    *report.mutable_lease() = LeaseToProto(run.lease);
    *report.mutable_progress() = ProgressToProto(
        {.timesteps = progress.timesteps,
         .policy_version = progress.updates,
         .steps_per_second = progress.steps_per_second,
         .recent_return = progress.recent_return,
         .avg_combined = progress.evaluation == nullptr
                             ? std::nullopt
                             : std::optional<double>(progress.evaluation->avg_combined),
         .evaluation_step = progress.evaluation == nullptr
                                ? std::nullopt
                                : std::optional<int64_t>(progress.evaluation->step)},
        progress.total_timesteps);
    v1::ReportProgressResponse reported;
    const absl::Status status =
        CallUnary(*coordinator_, &v1::CoordinatorService::Stub::ReportProgress, report, reported,
                  options_.rpc_timeout, "coordinator");
    if (IsLeaseLost(status)) run.Lose();
    if (run.lost) return;

    if (step->checkpoint.has_value()) {
      const absl::Status stored = PutCheckpoint(run, *step->checkpoint, step->evaluation_log);
      if (!stored.ok()) {
        if (run.lost || stopping_.HasBeenNotified()) return;
        Finish(run, v1::RUN_STATE_FAILED, stored.ToString());
        return;
      }
    }
    if (step->complete) {
      Finish(run, v1::RUN_STATE_COMPLETED, "");
      Log(LogLevel::kInfo, "run complete", {{"run_id", run.lease.run_id}});
      return;
    }
  }
}

}  // namespace dcs::services
