// Copyright 2026 The DCS Authors.
//
// CoordinatorService's runs and leases: the store's runs, evaluations and checkpoints
// (coordinator/store.h) and the runs' directories (coordinator/run_files.h) on the wire; and
// the store's backups.

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "coordinator/run_files.h"
#include "coordinator/run_removal.h"
#include "coordinator/run_submission.h"
#include "dcs/v1/trajectory.pb.h"
#include "services/coordinator/coordinator_service.h"
#include "services/coordinator/record_proto.h"
#include "services/evaluation_grid_proto.h"
#include "services/grpc_status.h"
#include "services/log.h"
#include "services/piece_reactors.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

constexpr char kDefaultConfigName[] = "run.yaml";

// The question (ParkedCalls) a worker of `numerics` asks for work: workers of other numerics
// may not take the same runs. Never empty, so that such calls always share it.
std::string NumericsQuestion(absl::string_view numerics) {
  return absl::StrCat("numerics ", numerics);
}

// PutCheckpoint's stream: the pieces of one checkpoint and of its evaluation log's new part,
// stored once the learner has sent them all. Owned by gRPC from construction until OnDone.
class CheckpointReader final : public grpc::ServerReadReactor<v1::PutCheckpointRequest> {
 public:
  // The lease, the checkpoint, and its evaluation log from evaluation `first` on.
  using Store = std::function<absl::Status(const coordinator::LeaseKey&,
                                           const run::PackedCheckpoint&, int64_t first,
                                           const v1::EvaluationLog&)>;
  using Count = std::function<void(const absl::Status&)>;

  // Borrows `calls` (must outlive the call), whose pool runs `store`.
  CheckpointReader(ServedCalls& calls, Store store, Count count)
      : calls_(calls), store_(std::move(store)), count_(std::move(count)) {
    StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    if (!ok) {  // the learner sent every piece
      calls_.Offload([this] { return Complete(); },
                     [this](const absl::Status& status) { End(status); });
      return;
    }
    const absl::Status added = Add();
    if (added.ok()) {
      StartRead(&request_);
      return;
    }
    End(added);
  }

  void OnDone() override { delete this; }

 private:
  absl::Status Add() {
    const bool first = !key_.has_value();
    if (first) {
      DCS_ASSIGN_OR_RETURN(key_, LeaseFromProto(request_.lease()));
      first_evaluation_ = request_.evaluations_before();
    }
    DCS_RETURN_IF_ERROR(AddCheckpointPiece(request_.checkpoint(), first, checkpoint_));
    if (log_.size() + request_.evaluation_log().size() > kMaxStreamedBytes) {
      return absl::ResourceExhaustedError(absl::StrCat(
          "the evaluation log of checkpoint ", checkpoint_.name, " is larger than ",
          kMaxStreamedBytes, " bytes"));
    }
    log_.append(request_.evaluation_log());
    return absl::OkStatus();
  }

  absl::Status Complete() {
    if (!key_.has_value()) return absl::InvalidArgumentError("the checkpoint stream was empty");
    v1::EvaluationLog log;
    if (!log.ParseFromString(log_)) {
      return absl::InvalidArgumentError(
          absl::StrCat("the evaluation log of checkpoint ", checkpoint_.name, " does not parse"));
    }
    return store_(*key_, checkpoint_, first_evaluation_, log);
  }

  void End(const absl::Status& status) {
    count_(status);
    Finish(ToGrpcStatus(status));
  }

  ServedCalls& calls_;
  const Store store_;
  const Count count_;
  v1::PutCheckpointRequest request_;
  std::optional<coordinator::LeaseKey> key_;  // from the first piece
  int64_t first_evaluation_ = 0;               // from the first piece
  run::PackedCheckpoint checkpoint_;
  std::string log_;
};

}  // namespace

grpc::ServerUnaryReactor* CoordinatorService::SubmitRun(grpc::CallbackServerContext* context,
                                                        const v1::SubmitRunRequest* request,
                                                        v1::SubmitRunResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
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
        runs_.store->runs().SubmitRun({.request_id = request->request_id(),
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
    parked_.Wake(kRunsTopic);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetRun(grpc::CallbackServerContext* context,
                                                     const v1::GetRunRequest* request,
                                                     v1::GetRunResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<v1::GetRunResponse> run = ReadRun(request->run_id());
    if (run.ok()) *response = *std::move(run);
    return run.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ListRuns(grpc::CallbackServerContext* context,
                                                       const v1::ListRunsRequest* /*request*/,
                                                       v1::ListRunsResponse* response) {
  return calls_.Offloaded(context, [this, response]() -> absl::Status {
    absl::StatusOr<std::vector<coordinator::RunRecord>> runs = runs_.store->runs().ListRuns();
    if (runs.ok()) {
      for (const coordinator::RunRecord& run : *runs) *response->add_runs() = RunToProto(run);
    }
    return runs.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::CancelRun(grpc::CallbackServerContext* context,
                                                        const v1::CancelRunRequest* request,
                                                        v1::CancelRunResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<coordinator::RunRecord> run =
        runs_.store->runs().CancelRun(request->run_id(), absl::Now());
    if (run.ok()) {
      Log(LogLevel::kInfo, "run cancelled", {{"run_id", run->id}});
      *response->mutable_run() = RunToProto(*run);
      watchers_.Notify(RunTopic(run->id));
    }
    return run.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::DeleteRuns(grpc::CallbackServerContext* context,
                                                         const v1::DeleteRunsRequest* request,
                                                         v1::DeleteRunsResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    const std::vector<std::string> run_ids(request->run_ids().begin(), request->run_ids().end());
    DCS_ASSIGN_OR_RETURN(const coordinator::RunRemoval removal,
                         coordinator::RemoveRuns(*runs_.store, runs_.data_dir, run_ids));
    for (const coordinator::RunRecord& run : removal.runs) {
      Log(LogLevel::kInfo, "run removed", {{"run_id", run.id}});
      *response->add_runs() = RunToProto(run);
    }
    RunsRemoved(removal.runs);
    LogLeftDirectories(removal.files);
    return absl::OkStatus();
  });
}

void CoordinatorService::RunsRemoved(const std::vector<coordinator::RunRecord>& runs) {
  for (const coordinator::RunRecord& run : runs) completed_logs_.Forget(run.id);
}

void CoordinatorService::LogLeftDirectories(const absl::Status& files) {
  if (files.ok()) return;
  Log(LogLevel::kWarning, "removed runs' directories left for the next start to remove",
      {{"error", files.ToString()}});
}

grpc::ServerWriteReactor<v1::RunFile>* CoordinatorService::GetRunFiles(
    grpc::CallbackServerContext* context, const v1::GetRunFilesRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::RunFile>>(context, [&] {
    auto get = [this, request]() -> absl::StatusOr<std::vector<v1::RunFile>> {
      DCS_ASSIGN_OR_RETURN(const coordinator::RunRecord run,
                           runs_.store->runs().GetRun(request->run_id()));
      DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::RunFile> files,
                           coordinator::ReadRunFiles(
                               coordinator::RunDirectory(runs_.data_dir, run.id)));
      return RunFilesToPieces(files);
    };
    return WritePiecesFromPool<v1::RunFile>(
        calls_, get, [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

grpc::ServerWriteReactor<v1::BackupPiece>* CoordinatorService::BackupStore(
    grpc::CallbackServerContext* context, const v1::BackupStoreRequest* /*request*/) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::BackupPiece>>(context, [&] {
    static std::atomic<int64_t> backups = 0;
    // Written beside the store (its disk, its permissions), read whole, and removed.
    const std::string path =
        (std::filesystem::path(runs_.data_dir) / absl::StrCat("backup-", ++backups, ".db"))
            .string();
    auto back_up = [this, path]() -> absl::StatusOr<std::vector<v1::BackupPiece>> {
      DCS_ASSIGN_OR_RETURN(const coordinator::BackupCounts counts, runs_.store->Backup(path));
      absl::StatusOr<std::string> bytes = ReadFile(path);
      std::error_code ignored;
      std::filesystem::remove(path, ignored);
      if (!bytes.ok()) return bytes.status();
      v1::BackupPiece header;
      header.set_size(static_cast<int64_t>(bytes->size()));
      header.set_sha256(run::Sha256Hex(*bytes));
      header.set_runs(counts.runs);
      header.set_sweeps(counts.sweeps);
      header.set_studies(counts.studies);
      Log(LogLevel::kInfo, "store backed up",
          {{"bytes", std::to_string(bytes->size())}, {"runs", std::to_string(counts.runs)}});
      return CutIntoMessages(std::move(header), *bytes, &v1::BackupPiece::mutable_data);
    };
    return WritePiecesFromPool<v1::BackupPiece>(
        calls_, back_up, [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

grpc::ServerUnaryReactor* CoordinatorService::AcquireRun(grpc::CallbackServerContext* context,
                                                         const v1::AcquireRunRequest* request,
                                                         v1::AcquireRunResponse* response) {
  return calls_.Serve<grpc::ServerUnaryReactor>(context, [&] {
    auto acquire = [this, request, response]() -> absl::StatusOr<bool> {
      DCS_ASSIGN_OR_RETURN(
          const std::optional<coordinator::LearnerLease> lease,
          runs_.store->runs().AcquireRun(request->holder(), request->address(),
                                         request->numerics(), absl::Now()));
      if (!lease.has_value()) return false;
      learner_leases_.Increment();
      watchers_.Notify(RunTopic(lease->run.id));
      Log(LogLevel::kInfo, "run leased",
          {{"run_id", lease->run.id}, {"learner", request->holder()},
           {"epoch", std::to_string(lease->key.epoch)},
           {"checkpoint", lease->run.checkpoint.empty() ? "none" : lease->run.checkpoint}});
      *response->mutable_lease() = LeaseToProto(lease->key);
      response->set_config(lease->run.submission.config);
      response->set_seed(lease->run.submission.seed);
      *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
      response->set_sweep_id(lease->run.sweep_id);
      response->set_condition(lease->condition);
      response->set_observe(lease->observe);
      return true;
    };
    // Learners of the same numerics find the same queued run.
    return AnswerOrPark(context, request->wait(), kRunsTopic,
                        NumericsQuestion(request->numerics()), acquire);
  });
}

grpc::ServerUnaryReactor* CoordinatorService::AcquireSlot(grpc::CallbackServerContext* context,
                                                          const v1::AcquireSlotRequest* request,
                                                          v1::AcquireSlotResponse* response) {
  return calls_.Serve<grpc::ServerUnaryReactor>(context, [&] {
    std::vector<coordinator::LeaseKey> complete_learners;
    for (const v1::Lease& learner : request->complete_learners()) {
      absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(learner);
      if (!key.ok()) return calls_.Answer(context, Annotate(key.status(), "complete_learners"));
      complete_learners.push_back(*std::move(key));
    }
    auto acquire = [this, request, response,
                    complete_learners = std::move(complete_learners)]() -> absl::StatusOr<bool> {
      DCS_ASSIGN_OR_RETURN(const std::optional<coordinator::SlotLease> lease,
                           runs_.store->runs().AcquireSlot(request->holder(),
                                                           request->numerics(),
                                                           complete_learners, absl::Now()));
      if (!lease.has_value()) return false;
      slot_leases_.Increment();
      watchers_.Notify(RunTopic(lease->key.run_id));  // its actors' numerics
      *response->mutable_lease() = LeaseToProto(lease->key);
      response->set_learner_address(lease->learner_address);
      response->set_learner_epoch(lease->learner_epoch);
      response->set_config(lease->config);
      response->set_seed(lease->seed);
      *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
      return true;
    };
    // Actors of the same numerics that skip the same runs find the same free slot.
    std::string question = NumericsQuestion(request->numerics());
    for (const v1::Lease& learner : request->complete_learners()) {
      absl::StrAppend(&question, " ", learner.run_id(), "@", learner.epoch());
    }
    return AnswerOrPark(context, request->wait(), kSlotsTopic, std::move(question),
                        std::move(acquire));
  });
}

grpc::ServerUnaryReactor* CoordinatorService::RenewLease(grpc::CallbackServerContext* context,
                                                         const v1::RenewLeaseRequest* request,
                                                         v1::RenewLeaseResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
    if (!key.ok()) return key.status();
    *response->mutable_lease_duration() = DurationToProto(runs_.lease_duration);
    return runs_.store->runs().RenewLease(*key, absl::Now());
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ReleaseLease(grpc::CallbackServerContext* context,
                                                           const v1::ReleaseLeaseRequest* request,
                                                           v1::ReleaseLeaseResponse* /*response*/) {
  return calls_.Offloaded(context, [this, request]() -> absl::Status {
    absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
    if (!key.ok()) return key.status();
    const absl::Status released = runs_.store->runs().ReleaseLease(*key, absl::Now());
    if (released.ok()) {
      watchers_.Notify(RunTopic(key->run_id));
      // A learner's run goes back to the queue; an actor's slot is free for another, unless
      // its run is complete.
      if (key->slot == coordinator::kLearnerSlot) {
        parked_.Wake(kRunsTopic);
      } else if (!request->run_complete()) {
        parked_.Wake(kSlotsTopic);
      }
    }
    return released;
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ReportProgress(
    grpc::CallbackServerContext* context, const v1::ReportProgressRequest* request,
    v1::ReportProgressResponse* /*response*/) {
  return calls_.Offloaded(context, [this, request]() -> absl::Status {
    absl::StatusOr<coordinator::LeaseKey> key = LeaseFromProto(request->lease());
    if (!key.ok()) return key.status();
    const absl::Status reported = runs_.store->runs().ReportProgress(
        *key, ProgressFromProto(request->progress()), absl::Now());
    if (reported.ok()) watchers_.Notify(RunTopic(key->run_id));
    return reported;
  });
}

absl::Status CoordinatorService::StoreCheckpoint(const coordinator::LeaseKey& key,
                                                 const run::PackedCheckpoint& checkpoint,
                                                 int64_t first_evaluation,
                                                 const v1::EvaluationLog& log_since) {
  // Only the lease's holder writes the run's directory; checked again when indexing.
  DCS_RETURN_IF_ERROR(runs_.store->runs().RenewLease(key, absl::Now()));
  DCS_ASSIGN_OR_RETURN(const coordinator::CheckpointRecord stored,
                       coordinator::StoreCheckpoint(
                           coordinator::RunDirectory(runs_.data_dir, key.run_id), checkpoint,
                           first_evaluation, log_since, runs_.keep_checkpoints));
  DCS_RETURN_IF_ERROR(runs_.store->checkpoints().RecordCheckpoint(
      key, stored, coordinator::ScoreEvaluations(log_since), absl::Now()));
  watchers_.Notify(RunTopic(key.run_id));
  return absl::OkStatus();
}

grpc::ServerReadReactor<v1::PutCheckpointRequest>* CoordinatorService::PutCheckpoint(
    grpc::CallbackServerContext* context, v1::PutCheckpointResponse* /*response*/) {
  return calls_.Serve<grpc::ServerReadReactor<v1::PutCheckpointRequest>>(context, [&] {
    return new CheckpointReader(
        calls_,
        [this](const coordinator::LeaseKey& key, const run::PackedCheckpoint& checkpoint,
               int64_t first, const v1::EvaluationLog& log_since) {
          return StoreCheckpoint(key, checkpoint, first, log_since);
        },
        [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

grpc::ServerWriteReactor<v1::CheckpointPiece>* CoordinatorService::GetCheckpoint(
    grpc::CallbackServerContext* context, const v1::GetCheckpointRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::CheckpointPiece>>(context, [&] {
    auto get = [this, request]() -> absl::StatusOr<std::vector<v1::CheckpointPiece>> {
      DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request->lease()));
      if (key.slot != coordinator::kLearnerSlot) {
        return absl::InvalidArgumentError("a run's checkpoints are for its learner lease");
      }
      // Only the lease's holder resumes the run.
      DCS_RETURN_IF_ERROR(runs_.store->runs().RenewLease(key, absl::Now()));
      // The learner hosts the run now (it asks as it loads it): its slots are worth taking.
      parked_.Wake(kSlotsTopic);
      DCS_ASSIGN_OR_RETURN(const run::PackedCheckpoint checkpoint,
                           coordinator::LatestCheckpoint(
                               coordinator::RunDirectory(runs_.data_dir, key.run_id)));
      return CheckpointToPieces(checkpoint);
    };
    return WritePiecesFromPool<v1::CheckpointPiece>(
        calls_, get, [this](const absl::Status& status) {
          // NOT_FOUND is the answer for a run without a checkpoint yet, not a refusal.
          if (!absl::IsNotFound(status)) rejected_.Count(status);
        });
  });
}

grpc::ServerUnaryReactor* CoordinatorService::FinishRun(grpc::CallbackServerContext* context,
                                                        const v1::FinishRunRequest* request,
                                                        v1::FinishRunResponse* /*response*/) {
  return calls_.Offloaded(context, [this, request]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request->lease()));
    DCS_ASSIGN_OR_RETURN(const coordinator::RunState state, RunStateFromProto(request->state()));
    DCS_RETURN_IF_ERROR(runs_.store->runs().FinishRun(key, state, request->error(), absl::Now()));
    // Once: a second FinishRun of the same lease is refused, the lease being freed.
    if (state == coordinator::RunState::kFailed) runs_failed_.Increment();
    watchers_.Notify(RunTopic(key.run_id));
    Log(LogLevel::kInfo, "run finished",
        {{"run_id", key.run_id}, {"state", std::string(NameOf(coordinator::kRunStateNames, state))},
         {"error", request->error()}});
    return absl::OkStatus();
  });
}

grpc::ServerReadReactor<v1::SubmitEvaluationRequest>* CoordinatorService::SubmitEvaluation(
    grpc::CallbackServerContext* context, v1::SubmitEvaluationResponse* /*response*/) {
  return calls_.Serve<grpc::ServerReadReactor<v1::SubmitEvaluationRequest>>(context, [&] {
    auto submit = [this](PieceJoiner<v1::SubmitEvaluationRequest>& joined) -> absl::Status {
      const v1::SubmitEvaluationRequest& request = joined.header();
      DCS_ASSIGN_OR_RETURN(const coordinator::LeaseKey key, LeaseFromProto(request.lease()));
      v1::PolicyWeights weights;  // checked here, so that actors are given what parses
      DCS_RETURN_IF_ERROR(joined.Parse(weights));
      DCS_RETURN_IF_ERROR(runs_.store->evaluations().SubmitEvaluation(
          key,
          {.policy_version = request.policy_version(),
           .step = request.step(),
           .contexts = request.contexts(),
           .episodes = request.episodes(),
           .weights = std::move(joined.payload())},
          absl::Now()));
      parked_.Wake(kEvaluationJobsTopic);
      return absl::OkStatus();
    };
    return new JoiningReader<v1::SubmitEvaluationRequest>(
        calls_,
        PieceJoiner<v1::SubmitEvaluationRequest>(&v1::SubmitEvaluationRequest::mutable_weights,
                                                 "the evaluation's policy"),
        submit, [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

grpc::ServerReadReactor<v1::SubmitGridEvaluationRequest>*
CoordinatorService::SubmitGridEvaluation(grpc::CallbackServerContext* context,
                                         v1::SubmitGridEvaluationResponse* response) {
  return calls_.Serve<grpc::ServerReadReactor<v1::SubmitGridEvaluationRequest>>(context, [&] {
    auto submit = [this, response](PieceJoiner<v1::SubmitGridEvaluationRequest>& joined)
        -> absl::Status {
      const v1::SubmitGridEvaluationRequest& request = joined.header();
      // The grid's features are resolved by the actors, against the run's environment.
      DCS_ASSIGN_OR_RETURN(const int cells, GridCellCount(request.grid()));
      v1::PolicyWeights weights;  // checked here, so that actors are given what parses
      DCS_RETURN_IF_ERROR(joined.Parse(weights));
      DCS_ASSIGN_OR_RETURN(const int64_t key, runs_.store->evaluations().SubmitGridEvaluation(
                                                  {.request_id = request.request_id(),
                                                   .run_id = request.run_id(),
                                                   .cells = cells,
                                                   .episodes = request.episodes(),
                                                   .grid = request.grid().SerializeAsString(),
                                                   .weights = std::move(joined.payload())},
                                                  absl::Now()));
      response->set_evaluation_key(key);
      parked_.Wake(kEvaluationJobsTopic);
      return absl::OkStatus();
    };
    return new JoiningReader<v1::SubmitGridEvaluationRequest>(
        calls_,
        PieceJoiner<v1::SubmitGridEvaluationRequest>(
            &v1::SubmitGridEvaluationRequest::mutable_weights, "the grid evaluation's policy"),
        submit, [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetEvaluation(
    grpc::CallbackServerContext* context, const v1::GetEvaluationRequest* request,
    v1::GetEvaluationResponse* response) {
  return calls_.Serve<grpc::ServerUnaryReactor>(context, [&] {
    // Answers with how far the evaluation is; waits (with a `wait`) until it is done.
    auto progress = [this, request, response]() -> absl::StatusOr<bool> {
      DCS_ASSIGN_OR_RETURN(
          const coordinator::EvaluationProgress evaluation,
          runs_.store->evaluations().GetEvaluation(request->run_id(), request->policy_version()));
      response->Clear();
      response->set_contexts(evaluation.contexts);
      response->set_done(evaluation.done);
      for (const coordinator::ContextReturns& result : evaluation.results) {
        *response->add_results() = ContextReturnsToProto(result);
      }
      return evaluation.done == evaluation.contexts;
    };
    return AnswerOrPark(context, request->wait(),
                        EvaluationTopic(request->run_id(), request->policy_version()),
                        /*question=*/"", progress);
  });
}

grpc::ServerWriteReactor<v1::AcquireEvaluationResponse>* CoordinatorService::AcquireEvaluation(
    grpc::CallbackServerContext* context, const v1::AcquireEvaluationRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::AcquireEvaluationResponse>>(context, [&] {
    // The grant's messages: a header without jobs when none is open.
    auto acquire =
        [this, request]() -> absl::StatusOr<std::vector<v1::AcquireEvaluationResponse>> {
      DCS_ASSIGN_OR_RETURN(std::optional<coordinator::EvaluationGrant> grant,
                           runs_.store->evaluations().AcquireEvaluationJobs(
                               request->holder(), request->numerics(), request->max_jobs(),
                               AliveActors(), request->grid_cells(), absl::Now()));
      v1::AcquireEvaluationResponse header;
      if (!grant.has_value()) return std::vector{std::move(header)};
      evaluation_leases_.Increment(static_cast<double>(grant->jobs.size()));
      for (const coordinator::EvaluationJobKey& job : grant->jobs) {
        *header.add_jobs() = EvaluationJobToProto(job);
      }
      header.set_config(std::move(grant->config));
      header.set_episodes(grant->episodes);
      if (!grant->grid.empty() && !header.mutable_grid()->ParseFromString(grant->grid)) {
        return absl::DataLossError(absl::StrCat("the grid of the evaluation of ",
                                                grant->jobs.front().run_id, " with key ",
                                                grant->jobs.front().policy_version,
                                                " does not parse"));
      }
      *header.mutable_lease_duration() = DurationToProto(runs_.lease_duration);
      return CutIntoMessages(std::move(header), grant->weights,
                             &v1::AcquireEvaluationResponse::mutable_weights);
    };
    // The last attempt's messages, which the answer writes: one with no jobs until an attempt
    // (a server that stops expires a parked call without one).
    auto messages = std::make_shared<std::vector<v1::AcquireEvaluationResponse>>(1);
    auto* writer = new PiecesWriter<v1::AcquireEvaluationResponse>();
    // Actors of the same numerics find the same open job, and a grid's only if they take grids.
    AnswerOrPark(
        *context, request->wait(), kEvaluationJobsTopic,
        absl::StrCat(NumericsQuestion(request->numerics()), request->grid_cells() ? " grid" : ""),
        [acquire, messages]() -> absl::StatusOr<bool> {
          DCS_ASSIGN_OR_RETURN(*messages, acquire());
          return !messages->front().jobs().empty();
        },
        [writer, messages](const absl::Status& status) {
          if (status.ok()) {
            writer->Start(std::move(*messages));
          } else {
            writer->Start(status);
          }
        });
    return writer;
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ReportEvaluation(
    grpc::CallbackServerContext* context, const v1::ReportEvaluationRequest* request,
    v1::ReportEvaluationResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    if (request->results().empty()) {
      return absl::InvalidArgumentError("the report holds no job's result");
    }
    std::vector<coordinator::JobResult> results;
    for (const v1::JobResult& delivered : request->results()) {
      DCS_ASSIGN_OR_RETURN(coordinator::EvaluationJobKey job,
                           EvaluationJobFromProto(delivered.job()));
      results.push_back({.job = std::move(job),
                         .result = ContextReturnsFromProto(delivered.result())});
    }
    DCS_ASSIGN_OR_RETURN(const std::vector<bool> duplicate,
                         runs_.store->evaluations().ReportEvaluationJobs(results));
    for (const bool delivered_before : duplicate) response->add_duplicate(delivered_before);
    for (const coordinator::JobResult& delivered : results) {
      parked_.Wake(EvaluationTopic(delivered.job.run_id, delivered.job.policy_version));
    }
    return absl::OkStatus();
  });
}

}  // namespace dcs::services
