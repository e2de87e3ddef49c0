// Copyright 2026 The DCS Authors.
//
// CoordinatorService's studies: the store's ask-and-tell (coordinator/study_table.h) on the
// wire.

#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "services/coordinator/coordinator_service.h"
#include "services/coordinator/study_proto.h"
#include "services/log.h"

namespace dcs::services {

grpc::ServerUnaryReactor* CoordinatorService::CreateStudy(grpc::CallbackServerContext* context,
                                                          const v1::CreateStudyRequest* request,
                                                          v1::CreateStudyResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(coordinator::StudyRecord study, StudyFromProto(request->study()));
    study.submission.request_id = request->request_id();
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord created,
                         runs_.store->studies().CreateStudy(study.submission, absl::Now()));
    Log(LogLevel::kInfo, "study created",
        {{"study_id", created.id}, {"name", created.submission.name}});
    *response->mutable_study() = StudyToProto(created);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetStudy(grpc::CallbackServerContext* context,
                                                       const v1::GetStudyRequest* request,
                                                       v1::GetStudyResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study,
                         runs_.store->studies().GetStudy(request->study_id()));
    DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::StudyTrial> trials,
                         runs_.store->studies().ListStudyTrials(request->study_id()));
    *response->mutable_study() = StudyToProto(study);
    for (const coordinator::StudyTrial& trial : trials) {
      *response->add_trials() = StudyTrialToProto(trial);
    }
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ListStudies(
    grpc::CallbackServerContext* context, const v1::ListStudiesRequest* /*request*/,
    v1::ListStudiesResponse* response) {
  return calls_.Offloaded(context, [this, response]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::StudyRecord> studies,
                         runs_.store->studies().ListStudies());
    for (const coordinator::StudyRecord& study : studies) {
      *response->add_studies() = StudyToProto(study);
    }
    return absl::OkStatus();
  });
}

namespace {

// A study a sweep drives is asked and told by the coordinator only: FAILED_PRECONDITION for a
// client's ask, tell or report, naming the sweep.
absl::Status RequireAskAndTell(coordinator::Store& store, const std::string& study_id) {
  DCS_ASSIGN_OR_RETURN(const coordinator::StudyRecord study, store.studies().GetStudy(study_id));
  if (study.sweep_id.empty()) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat(
      study_id, " is driven by ", study.sweep_id, ": the coordinator asks and tells it"));
}

}  // namespace

grpc::ServerUnaryReactor* CoordinatorService::AskTrial(grpc::CallbackServerContext* context,
                                                       const v1::AskTrialRequest* request,
                                                       v1::AskTrialResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    DCS_RETURN_IF_ERROR(RequireAskAndTell(*runs_.store, request->study_id()));
    DCS_ASSIGN_OR_RETURN(
        const coordinator::StudyTrial trial,
        runs_.store->studies().AskTrial(request->study_id(), request->request_id(), absl::Now()));
    *response->mutable_trial() = StudyTrialToProto(trial);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::TellTrial(grpc::CallbackServerContext* context,
                                                        const v1::TellTrialRequest* request,
                                                        v1::TellTrialResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    const std::optional<coordinator::TrialState> state =
        FindByName(coordinator::kTrialStateNames, request->state());
    if (!state.has_value()) {
      return absl::InvalidArgumentError(
          absl::StrCat("unknown trial state '", request->state(), "'"));
    }
    DCS_RETURN_IF_ERROR(RequireAskAndTell(*runs_.store, request->study_id()));
    DCS_ASSIGN_OR_RETURN(const coordinator::StudyTrial trial,
                         runs_.store->studies().TellTrial(request->study_id(), request->number(),
                                                          *state, request->value(), absl::Now()));
    *response->mutable_trial() = StudyTrialToProto(trial);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ReportTrial(grpc::CallbackServerContext* context,
                                                          const v1::ReportTrialRequest* request,
                                                          v1::ReportTrialResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    DCS_RETURN_IF_ERROR(RequireAskAndTell(*runs_.store, request->study_id()));
    DCS_ASSIGN_OR_RETURN(const bool prune,
                         runs_.store->studies().ReportTrial(request->study_id(), request->number(),
                                                            request->step(), request->value()));
    response->set_prune(prune);
    return absl::OkStatus();
  });
}

}  // namespace dcs::services
