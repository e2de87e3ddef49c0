// Copyright 2026 The DCS Authors.
//
// CoordinatorService's runs and leases: the run store (coordinator/run_store.h) and the runs'
// directories (coordinator/run_files.h) on the wire.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "coordinator/run_files.h"
#include "coordinator/run_submission.h"
#include "services/coordinator_service.h"
#include "services/log.h"
#include "services/run_proto.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

constexpr char kDefaultConfigName[] = "run.yaml";

}  // namespace

grpc::ServerUnaryReactor* CoordinatorService::SubmitRun(grpc::CallbackServerContext* context,
                                                        const v1::SubmitRunRequest* request,
                                                        v1::SubmitRunResponse* response) {
  auto submit = [&]() -> absl::Status {
    if (request->request_id().empty()) {
      return absl::InvalidArgumentError("request_id is empty: a client names each submission");
    }
    const std::string config_name =
        request->config_name().empty() ? kDefaultConfigName : request->config_name();
    std::optional<uint64_t> seed;
    if (request->has_seed()) seed = request->seed();
    DCS_ASSIGN_OR_RETURN(run::RunRequest run,
                         coordinator::CheckSubmittedRun(request->config(), config_name, seed));
    DCS_ASSIGN_OR_RETURN(
        const coordinator::RunRecord record,
        runs_.store->SubmitRun({.request_id = request->request_id(),
                                .config = run.config_text,
                                .seed = run.spec.seed,
                                .env = run.spec.env,
                                .n_envs = run.spec.n_envs,
                                .total_timesteps = run.spec.total_timesteps},
                               absl::Now()));
    // The run's directory holds its config, as `dcs train` writes it (again, on a retry).
    run.dir = coordinator::RunDirectory(runs_.data_dir, record.id);
    DCS_RETURN_IF_ERROR(run::CreateRunDirectory(run));
    Log(LogLevel::kInfo, "run submitted",
        {{"run_id", record.id}, {"env", record.submission.env},
         {"seed", std::to_string(record.submission.seed)}});
    *response->mutable_run() = RunToProto(record);
    return absl::OkStatus();
  };
  return Finish(context, submit());
}

grpc::ServerUnaryReactor* CoordinatorService::GetRun(grpc::CallbackServerContext* context,
                                                     const v1::GetRunRequest* request,
                                                     v1::GetRunResponse* response) {
  absl::StatusOr<coordinator::RunRecord> run = runs_.store->GetRun(request->run_id());
  if (run.ok()) *response->mutable_run() = RunToProto(*run);
  return Finish(context, run.status());
}

grpc::ServerUnaryReactor* CoordinatorService::ListRuns(grpc::CallbackServerContext* context,
                                                       const v1::ListRunsRequest* /*request*/,
                                                       v1::ListRunsResponse* response) {
  absl::StatusOr<std::vector<coordinator::RunRecord>> runs = runs_.store->ListRuns();
  if (runs.ok()) {
    for (const coordinator::RunRecord& run : *runs) *response->add_runs() = RunToProto(run);
  }
  return Finish(context, runs.status());
}

grpc::ServerUnaryReactor* CoordinatorService::CancelRun(grpc::CallbackServerContext* context,
                                                        const v1::CancelRunRequest* request,
                                                        v1::CancelRunResponse* response) {
  absl::StatusOr<coordinator::RunRecord> run =
      runs_.store->CancelRun(request->run_id(), absl::Now());
  if (run.ok()) {
    Log(LogLevel::kInfo, "run cancelled", {{"run_id", run->id}});
    *response->mutable_run() = RunToProto(*run);
  }
  return Finish(context, run.status());
}

grpc::ServerUnaryReactor* CoordinatorService::GetRunFiles(grpc::CallbackServerContext* context,
                                                          const v1::GetRunFilesRequest* request,
                                                          v1::GetRunFilesResponse* response) {
  auto get = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::RunRecord run,
                         runs_.store->GetRun(request->run_id()));
    DCS_ASSIGN_OR_RETURN(std::vector<coordinator::RunFile> files,
                         coordinator::ReadRunFiles(
                             coordinator::RunDirectory(runs_.data_dir, run.id)));
    for (coordinator::RunFile& file : files) {
      v1::RunFile& out = *response->add_files();
      out.set_path(std::move(file.path));
      out.set_contents(std::move(file.contents));
    }
    return absl::OkStatus();
  };
  return Finish(context, get());
}

grpc::ServerUnaryReactor* CoordinatorService::AcquireRun(grpc::CallbackServerContext* context,
                                                         const v1::AcquireRunRequest* request,
                                                         v1::AcquireRunResponse* response) {
  auto acquire = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(
        const std::optional<coordinator::LearnerLease> lease,
        runs_.store->AcquireRun(request->holder(), request->address(), request->numerics(),
                                absl::Now()));
    if (!lease.has_value()) return absl::OkStatus();
    absl::StatusOr<run::PackedCheckpoint> checkpoint = coordinator::LatestCheckpoint(
        coordinator::RunDirectory(runs_.data_dir, lease->run.id));
    if (checkpoint.ok()) {
      *response->mutable_checkpoint() = CheckpointToProto(*checkpoint);
    } else if (!absl::IsNotFound(checkpoint.status())) {
      // The lease stays granted; it lapses, and the run is retried, unless an operator acts.
      return checkpoint.status();
    }
    learner_leases_.Increment();
    Log(LogLevel::kInfo, "run leased",
        {{"run_id", lease->run.id}, {"learner", request->holder()},
         {"epoch", std::to_string(lease->key.epoch)},
         {"checkpoint", checkpoint.ok() ? checkpoint->name : "none"}});
    *response->mutable_lease() = LeaseToProto(lease->key);
    response->set_config(lease->run.submission.config);
    response->set_seed(lease->run.submission.seed);
    *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
    return absl::OkStatus();
  };
  return Finish(context, acquire());
}

grpc::ServerUnaryReactor* CoordinatorService::AcquireSlot(grpc::CallbackServerContext* context,
                                                          const v1::AcquireSlotRequest* request,
                                                          v1::AcquireSlotResponse* response) {
  const std::vector<std::string> except(request->except_run_ids().begin(),
                                        request->except_run_ids().end());
  absl::StatusOr<std::optional<coordinator::SlotLease>> lease =
      runs_.store->AcquireSlot(request->holder(), request->numerics(), except, absl::Now());
  if (lease.ok() && lease->has_value()) {
    const coordinator::SlotLease& slot = **lease;
    slot_leases_.Increment();
    *response->mutable_lease() = LeaseToProto(slot.key);
    response->set_learner_address(slot.learner_address);
    response->set_learner_epoch(slot.learner_epoch);
    response->set_config(slot.config);
    response->set_seed(slot.seed);
    *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
  }
  return Finish(context, lease.status());
}

grpc::ServerUnaryReactor* CoordinatorService::RenewLease(grpc::CallbackServerContext* context,
                                                         const v1::RenewLeaseRequest* request,
                                                         v1::RenewLeaseResponse* response) {
  absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
  if (!key.ok()) return Finish(context, key.status());
  *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
  return Finish(context, runs_.store->RenewLease(*key, absl::Now()));
}

grpc::ServerUnaryReactor* CoordinatorService::ReleaseLease(grpc::CallbackServerContext* context,
                                                           const v1::ReleaseLeaseRequest* request,
                                                           v1::ReleaseLeaseResponse* /*response*/) {
  absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
  if (!key.ok()) return Finish(context, key.status());
  return Finish(context, runs_.store->ReleaseLease(*key, absl::Now()));
}

grpc::ServerUnaryReactor* CoordinatorService::ReportProgress(
    grpc::CallbackServerContext* context, const v1::ReportProgressRequest* request,
    v1::ReportProgressResponse* /*response*/) {
  absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
  if (!key.ok()) return Finish(context, key.status());
  return Finish(context, runs_.store->ReportProgress(*key, ProgressFromProto(request->progress()),
                                                     absl::Now()));
}

grpc::ServerUnaryReactor* CoordinatorService::PutCheckpoint(
    grpc::CallbackServerContext* context, const v1::PutCheckpointRequest* request,
    v1::PutCheckpointResponse* /*response*/) {
  auto put = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request->lease()));
    // Only the lease's holder writes the run's directory; checked again when indexing.
    DCS_RETURN_IF_ERROR(runs_.store->RenewLease(key, absl::Now()));
    DCS_ASSIGN_OR_RETURN(const coordinator::CheckpointRecord stored,
                         coordinator::StoreCheckpoint(
                             coordinator::RunDirectory(runs_.data_dir, key.run_id),
                             CheckpointFromProto(request->checkpoint()),
                             request->evaluation_log(), runs_.keep_checkpoints));
    return runs_.store->RecordCheckpoint(key, stored, absl::Now());
  };
  return Finish(context, put());
}

grpc::ServerUnaryReactor* CoordinatorService::FinishRun(grpc::CallbackServerContext* context,
                                                        const v1::FinishRunRequest* request,
                                                        v1::FinishRunResponse* /*response*/) {
  auto finish = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request->lease()));
    DCS_ASSIGN_OR_RETURN(const coordinator::RunState state, RunStateFromProto(request->state()));
    DCS_RETURN_IF_ERROR(runs_.store->FinishRun(key, state, request->error(), absl::Now()));
    Log(LogLevel::kInfo, "run finished",
        {{"run_id", key.run_id}, {"state", std::string(NameOf(coordinator::kRunStateNames, state))},
         {"error", request->error()}});
    return absl::OkStatus();
  };
  return Finish(context, finish());
}

grpc::ServerUnaryReactor* CoordinatorService::SubmitEvaluation(
    grpc::CallbackServerContext* context, const v1::SubmitEvaluationRequest* request,
    v1::SubmitEvaluationResponse* /*response*/) {
  auto submit = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request->lease()));
    return runs_.store->SubmitEvaluation(
        key,
        {.policy_version = request->policy_version(),
         .step = request->step(),
         .contexts = request->contexts(),
         .episodes = request->episodes(),
         .weights = request->has_weights() ? request->weights().SerializeAsString() : ""},
        absl::Now());
  };
  return Finish(context, submit());
}

grpc::ServerUnaryReactor* CoordinatorService::GetEvaluation(
    grpc::CallbackServerContext* context, const v1::GetEvaluationRequest* request,
    v1::GetEvaluationResponse* response) {
  absl::StatusOr<coordinator::EvaluationProgress> evaluation =
      runs_.store->GetEvaluation(request->run_id(), request->policy_version());
  if (evaluation.ok()) {
    response->set_contexts(evaluation->contexts);
    response->set_done(evaluation->done);
    for (const coordinator::ContextReturns& result : evaluation->results) {
      *response->add_results() = ContextReturnsToProto(result);
    }
  }
  return Finish(context, evaluation.status());
}

grpc::ServerUnaryReactor* CoordinatorService::AcquireEvaluation(
    grpc::CallbackServerContext* context, const v1::AcquireEvaluationRequest* request,
    v1::AcquireEvaluationResponse* response) {
  auto acquire = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(
        const std::optional<coordinator::EvaluationJob> job,
        runs_.store->AcquireEvaluationJob(request->holder(), request->numerics(), absl::Now()));
    if (!job.has_value()) return absl::OkStatus();
    if (!response->mutable_weights()->ParseFromString(job->weights)) {
      // The job stays leased and lapses; the store holds what the learner sent, so this is a
      // bug, not bad input.
      return absl::InternalError(absl::StrCat("the stored policy of ",
                                              job->key.run_id, " version ",
                                              job->key.policy_version, " does not parse"));
    }
    evaluation_leases_.Increment();
    *response->mutable_job() = EvaluationJobToProto(job->key);
    response->set_config(job->config);
    response->set_episodes(job->episodes);
    *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
    return absl::OkStatus();
  };
  return Finish(context, acquire());
}

grpc::ServerUnaryReactor* CoordinatorService::ReportEvaluation(
    grpc::CallbackServerContext* context, const v1::ReportEvaluationRequest* request,
    v1::ReportEvaluationResponse* response) {
  auto report = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::EvaluationJobKey key,
                         EvaluationJobFromProto(request->job()));
    DCS_ASSIGN_OR_RETURN(const bool duplicate,
                         runs_.store->ReportEvaluationJob(
                             key, ContextReturnsFromProto(request->result())));
    response->set_duplicate(duplicate);
    return absl::OkStatus();
  };
  return Finish(context, report());
}

}  // namespace dcs::services
