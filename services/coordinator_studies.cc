// Copyright 2026 The DCS Authors.
//
// CoordinatorService's studies: the run store's ask-and-tell (coordinator/run_store.h) on the
// wire.

#include <string>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "services/coordinator_service.h"
#include "services/log.h"
#include "services/study_proto.h"

namespace dcs::services {

grpc::ServerUnaryReactor* CoordinatorService::CreateStudy(grpc::CallbackServerContext* context,
                                                          const v1::CreateStudyRequest* request,
                                                          v1::CreateStudyResponse* response) {
  auto create = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(coordinator::StudyRecord study, StudyFromProto(request->study()));
    study.submission.request_id = request->request_id();
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord created,
                         runs_.store->CreateStudy(study.submission, absl::Now()));
    Log(LogLevel::kInfo, "study created",
        {{"study_id", created.id}, {"name", created.submission.name}});
    *response->mutable_study() = StudyToProto(created);
    return absl::OkStatus();
  };
  return Finish(context, create());
}

grpc::ServerUnaryReactor* CoordinatorService::GetStudy(grpc::CallbackServerContext* context,
                                                       const v1::GetStudyRequest* request,
                                                       v1::GetStudyResponse* response) {
  auto get = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study,
                         runs_.store->GetStudy(request->study_id()));
    DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::StudyTrial> trials,
                         runs_.store->ListStudyTrials(request->study_id()));
    *response->mutable_study() = StudyToProto(study);
    for (const coordinator::StudyTrial& trial : trials) {
      *response->add_trials() = StudyTrialToProto(trial);
    }
    return absl::OkStatus();
  };
  return Finish(context, get());
}

grpc::ServerUnaryReactor* CoordinatorService::AskTrial(grpc::CallbackServerContext* context,
                                                       const v1::AskTrialRequest* request,
                                                       v1::AskTrialResponse* response) {
  absl::StatusOr<coordinator::StudyTrial> trial =
      runs_.store->AskTrial(request->study_id(), request->request_id(), absl::Now());
  if (trial.ok()) *response->mutable_trial() = StudyTrialToProto(*trial);
  return Finish(context, trial.status());
}

grpc::ServerUnaryReactor* CoordinatorService::TellTrial(grpc::CallbackServerContext* context,
                                                        const v1::TellTrialRequest* request,
                                                        v1::TellTrialResponse* response) {
  auto tell = [&]() -> absl::Status {
    const std::optional<coordinator::TrialState> state =
        FindByName(coordinator::kTrialStateNames, request->state());
    if (!state.has_value()) {
      return absl::InvalidArgumentError(
          absl::StrCat("unknown trial state '", request->state(), "'"));
    }
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyTrial trial,
                         runs_.store->TellTrial(request->study_id(), request->number(), *state,
                                                request->value(), absl::Now()));
    *response->mutable_trial() = StudyTrialToProto(trial);
    return absl::OkStatus();
  };
  return Finish(context, tell());
}

grpc::ServerUnaryReactor* CoordinatorService::ReportTrial(grpc::CallbackServerContext* context,
                                                          const v1::ReportTrialRequest* request,
                                                          v1::ReportTrialResponse* response) {
  absl::StatusOr<bool> prune = runs_.store->ReportTrial(request->study_id(), request->number(),
                                                        request->step(), request->value());
  if (prune.ok()) response->set_prune(*prune);
  return Finish(context, prune.status());
}

}  // namespace dcs::services
