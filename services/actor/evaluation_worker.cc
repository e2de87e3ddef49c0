// Copyright 2026 The DCS Authors.
#include "services/actor/evaluation_worker.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "actor/context_grid.h"
#include "actor/evaluation.h"
#include "common/status_macros.h"
#include "env/env_registry.h"
#include "run/run_spec_yaml.h"
#include "services/backoff.h"
#include "services/channel.h"
#include "services/evaluation_grid_proto.h"
#include "services/log.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/time_proto.h"
#include "services/trajectory_proto.h"
#include "services/unary_call.h"

namespace dcs::services {
namespace {

constexpr BackoffPolicy kRetryBackoff{.initial = absl::Milliseconds(50),
                                      .max = absl::Seconds(1)};

std::string JobName(const v1::EvaluationJob& job) {
  if (job.policy_version() < 0) {  // a grid evaluation's key
    return absl::StrCat(job.run_id(), " grid ", -job.policy_version(), " cell ", job.context());
  }
  return absl::StrCat(job.run_id(), " v", job.policy_version(), " context ", job.context());
}

}  // namespace

EvaluationWorker::EvaluationWorker(EvaluationWorkerOptions options,
                                   prometheus::Registry& metrics, absl::Mutex& core)
    : options_(std::move(options)),
      coordinator_(v1::CoordinatorService::NewStub(OpenChannel(options_.coordinator_address))),
      jobs_(prometheus::BuildCounter()
                .Name("dcs_actor_evaluation_jobs_total")
                .Help("Evaluation jobs (one context of one policy version) this actor "
                      "delivered.")
                .Register(metrics)
                .Add({})),
      core_(core),
      thread_([this] { Work(); }) {}

EvaluationWorker::~EvaluationWorker() { Stop(); }

void EvaluationWorker::Stop() {
  if (!stopping_.HasBeenNotified()) stopping_.Notify();
  if (thread_.joinable()) thread_.join();
}

void EvaluationWorker::Work() {
  while (!stopping_.HasBeenNotified()) {
    const absl::Time asked = absl::Now();
    if (RunJobs()) continue;
    // The rest of the interval, if the coordinator answered before it (it could not be reached,
    // or is one that does not hold calls).
    stopping_.WaitForNotificationWithTimeout(options_.poll_interval - (absl::Now() - asked));
  }
}

absl::Status EvaluationWorker::Prepare(const v1::AcquireEvaluationResponse& grant,
                                       const v1::EvaluationJob& job, absl::string_view weights) {
  if (prepared_.run_id == job.run_id() && prepared_.policy_version == job.policy_version()) {
    return absl::OkStatus();
  }
  prepared_ = {};
  DCS_ASSIGN_OR_RETURN(run::RunSpec spec, run::ParseRunSpecYaml(grant.config(), job.run_id()));
  DCS_ASSIGN_OR_RETURN(prepared_.policy, PolicyFromBytes(weights));
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(prepared_.plan, run::PlanRun(spec, Env::Features()));
    if (grant.has_grid()) {
      DCS_ASSIGN_OR_RETURN(prepared_.grid_axes, GridAxesFromProto(Env::Features(), grant.grid()));
    }
    return absl::OkStatus();
  }));
  prepared_.spec = std::move(spec);
  prepared_.run_id = job.run_id();
  prepared_.policy_version = job.policy_version();
  return absl::OkStatus();
}

absl::StatusOr<v1::ContextReturns> EvaluationWorker::Evaluate(
    const v1::AcquireEvaluationResponse& grant, const v1::EvaluationJob& job,
    absl::string_view weights) {
  DCS_RETURN_IF_ERROR(Prepare(grant, job, weights));
  if (grant.has_grid()) return EvaluateGridCell(grant, job);
  const run::RunPlan& plan = prepared_.plan;
  const int context = job.context();
  if (context < 0 || static_cast<size_t>(context) >= plan.evaluation_contexts.size()) {
    return absl::InvalidArgumentError(absl::StrCat("the run has ",
                                                   plan.evaluation_contexts.size(),
                                                   " evaluation contexts, no context ", context));
  }
  const size_t index = static_cast<size_t>(context);
  actor::ContextResult result;
  DCS_RETURN_IF_ERROR(
      env::VisitEnvironment(prepared_.spec.env, [&]<typename Env>() -> absl::Status {
        absl::MutexLock on_core(&core_);
        DCS_ASSIGN_OR_RETURN(result, actor::EvaluateContext<Env>(
                                         *prepared_.policy, plan.slot, plan.feature,
                                         plan.evaluation_contexts[index], index, grant.episodes(),
                                         prepared_.spec.seed));
        return absl::OkStatus();
      }));
  return ContextReturnsToProto({.returns = std::move(result.returns), .seconds = result.seconds});
}

absl::StatusOr<v1::ContextReturns> EvaluationWorker::EvaluateGridCell(
    const v1::AcquireEvaluationResponse& grant, const v1::EvaluationJob& job) {
  const std::vector<actor::GridAxis>& axes = prepared_.grid_axes;
  if (job.context() < 0 || static_cast<size_t>(job.context()) >= actor::CellCount(axes)) {
    return absl::InvalidArgumentError(absl::StrCat("the grid has ", actor::CellCount(axes),
                                                   " cells, no cell ", job.context()));
  }
  const size_t cell = static_cast<size_t>(job.context());
  actor::ContextResult result;
  DCS_RETURN_IF_ERROR(
      env::VisitEnvironment(prepared_.spec.env, [&]<typename Env>() -> absl::Status {
        DCS_ASSIGN_OR_RETURN(const env::DynamicContextOptions options,
                             actor::GridCellOptions<Env>(prepared_.plan.slot, axes, cell));
        absl::MutexLock on_core(&core_);
        DCS_ASSIGN_OR_RETURN(result, actor::EvaluateGridCell<Env>(*prepared_.policy, options, axes,
                                                                  cell, grant.episodes(),
                                                                  grant.grid().seed()));
        return absl::OkStatus();
      }));
  return ContextReturnsToProto({.returns = std::move(result.returns), .seconds = result.seconds});
}

bool EvaluationWorker::RunJobs() {
  v1::AcquireEvaluationRequest request;
  request.set_holder(options_.holder);
  request.set_numerics(options_.numerics);
  request.set_max_jobs(jobs_wanted_);
  request.set_grid_cells(true);
  *request.mutable_wait() = DurationToProto(options_.poll_interval);
  PieceJoiner<v1::AcquireEvaluationResponse> reply(
      &v1::AcquireEvaluationResponse::mutable_weights, "the evaluation's policy");
  const absl::Status acquired = CallServerStream(
      *coordinator_, &v1::CoordinatorService::Stub::AcquireEvaluation, request,
      options_.rpc_timeout, "coordinator",
      [&](v1::AcquireEvaluationResponse& message) { return reply.Add(std::move(message)); });
  const v1::AcquireEvaluationResponse& grant = reply.header();
  if (!acquired.ok() || grant.jobs().empty()) {
    if (!acquired.ok() && !IsTransient(acquired)) {
      Log(LogLevel::kWarning, "cannot take evaluation jobs", {{"error", acquired.ToString()}});
    }
    return false;
  }
  const absl::Time start = absl::Now();
  v1::ReportEvaluationRequest report;
  for (const v1::EvaluationJob& job : grant.jobs()) {
    absl::StatusOr<v1::ContextReturns> result = Evaluate(grant, job, reply.payload());
    if (!result.ok()) {
      Log(LogLevel::kError, "cannot run an evaluation job",
          {{"job", JobName(job)}, {"error", result.status().ToString()}});
      return true;  // the jobs lapse; nothing here can run them
    }
    v1::JobResult& delivered = *report.add_results();
    *delivered.mutable_job() = job;
    *delivered.mutable_result() = *std::move(result);
  }
  const absl::Duration per_job = (absl::Now() - start) / grant.jobs_size();
  const absl::Duration lease = DurationFromProto(grant.lease_duration());
  jobs_wanted_ = static_cast<int>(std::clamp(
      absl::FDivDuration(lease / 2, std::max(per_job, absl::Nanoseconds(1))), 1.0,
      static_cast<double>(options_.max_jobs)));
  v1::ReportEvaluationResponse reported;
  const absl::Status status = CallWithRetries(
      *coordinator_, &v1::CoordinatorService::Stub::ReportEvaluation, report, reported,
      options_.rpc_timeout, "coordinator", kRetryBackoff,
      [&](const absl::Status&) { return !stopping_.HasBeenNotified(); });
  if (status.ok()) {
    jobs_.Increment(report.results_size());
  } else {
    Log(LogLevel::kWarning, "evaluation jobs not delivered",
        {{"first_job", JobName(grant.jobs(0))},
         {"jobs", std::to_string(grant.jobs_size())},
         {"error", status.ToString()}});
  }
  return true;
}

}  // namespace dcs::services
