// Copyright 2026 The DCS Authors.
#include "services/cli/study_client.h"

#include <grpcpp/grpcpp.h>

#include <filesystem>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/store.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/channel.h"
#include "services/coordinator/study_proto.h"
#include "services/unary_call.h"

namespace dcs::services::cli {
namespace {

using coordinator::StudyRecord;
using coordinator::StudyTrial;

class LocalStudies : public StudyClient {
 public:
  explicit LocalStudies(std::unique_ptr<coordinator::Store> store) : store_(std::move(store)) {}

  absl::StatusOr<StudyRecord> Create(const coordinator::StudySubmission& submission) override {
    return store_->studies().CreateStudy(submission, absl::Now());
  }
  absl::StatusOr<StudyRecord> Get(const std::string& study_id) override {
    return store_->studies().GetStudy(study_id);
  }
  absl::StatusOr<std::vector<StudyRecord>> List() override {
    return store_->studies().ListStudies();
  }
  absl::StatusOr<std::vector<StudyTrial>> Trials(const std::string& study_id) override {
    return store_->studies().ListStudyTrials(study_id);
  }
  absl::StatusOr<StudyTrial> Ask(const std::string& study_id,
                                 const std::string& request_id) override {
    return store_->studies().AskTrial(study_id, request_id, absl::Now());
  }
  absl::StatusOr<StudyTrial> Tell(const std::string& study_id, int64_t number,
                                  coordinator::TrialState state, double value) override {
    return store_->studies().TellTrial(study_id, number, state, value, absl::Now());
  }
  absl::StatusOr<bool> Report(const std::string& study_id, int64_t number, int64_t step,
                              double value) override {
    return store_->studies().ReportTrial(study_id, number, step, value);
  }

 private:
  std::unique_ptr<coordinator::Store> store_;
};

class RemoteStudies : public StudyClient {
 public:
  RemoteStudies(std::string address, absl::Duration timeout)
      : address_(std::move(address)),
        timeout_(timeout),
        stub_(v1::CoordinatorService::NewStub(OpenChannel(address_))) {}

  absl::StatusOr<StudyRecord> Create(const coordinator::StudySubmission& submission) override {
    v1::CreateStudyRequest request;
    request.set_request_id(submission.request_id);
    *request.mutable_study() = StudyToProto({.submission = submission});
    v1::CreateStudyResponse response;
    DCS_RETURN_IF_ERROR(Call(&v1::CoordinatorService::Stub::CreateStudy, request, response));
    return StudyFromProto(response.study());
  }
  absl::StatusOr<StudyRecord> Get(const std::string& study_id) override {
    DCS_ASSIGN_OR_RETURN(const v1::GetStudyResponse response, GetStudy(study_id));
    return StudyFromProto(response.study());
  }
  absl::StatusOr<std::vector<StudyRecord>> List() override {
    v1::ListStudiesResponse response;
    DCS_RETURN_IF_ERROR(
        Call(&v1::CoordinatorService::Stub::ListStudies, v1::ListStudiesRequest(), response));
    std::vector<StudyRecord> studies;
    for (const v1::Study& study : response.studies()) {
      DCS_ASSIGN_OR_RETURN(studies.emplace_back(), StudyFromProto(study));
    }
    return studies;
  }
  absl::StatusOr<std::vector<StudyTrial>> Trials(const std::string& study_id) override {
    DCS_ASSIGN_OR_RETURN(const v1::GetStudyResponse response, GetStudy(study_id));
    std::vector<StudyTrial> trials;
    for (const v1::StudyTrial& trial : response.trials()) {
      DCS_ASSIGN_OR_RETURN(trials.emplace_back(), StudyTrialFromProto(trial));
    }
    return trials;
  }
  absl::StatusOr<StudyTrial> Ask(const std::string& study_id,
                                 const std::string& request_id) override {
    v1::AskTrialRequest request;
    request.set_study_id(study_id);
    request.set_request_id(request_id);
    v1::AskTrialResponse response;
    DCS_RETURN_IF_ERROR(Call(&v1::CoordinatorService::Stub::AskTrial, request, response));
    return StudyTrialFromProto(response.trial());
  }
  absl::StatusOr<StudyTrial> Tell(const std::string& study_id, int64_t number,
                                  coordinator::TrialState state, double value) override {
    v1::TellTrialRequest request;
    request.set_study_id(study_id);
    request.set_number(number);
    request.set_state(std::string(NameOf(coordinator::kTrialStateNames, state)));
    request.set_value(value);
    v1::TellTrialResponse response;
    DCS_RETURN_IF_ERROR(Call(&v1::CoordinatorService::Stub::TellTrial, request, response));
    return StudyTrialFromProto(response.trial());
  }
  absl::StatusOr<bool> Report(const std::string& study_id, int64_t number, int64_t step,
                              double value) override {
    v1::ReportTrialRequest request;
    request.set_study_id(study_id);
    request.set_number(number);
    request.set_step(step);
    request.set_value(value);
    v1::ReportTrialResponse response;
    DCS_RETURN_IF_ERROR(Call(&v1::CoordinatorService::Stub::ReportTrial, request, response));
    return response.prune();
  }

 private:
  absl::StatusOr<v1::GetStudyResponse> GetStudy(const std::string& study_id) {
    v1::GetStudyRequest request;
    request.set_study_id(study_id);
    v1::GetStudyResponse response;
    DCS_RETURN_IF_ERROR(Call(&v1::CoordinatorService::Stub::GetStudy, request, response));
    return response;
  }

  // The call, tried three times with backoff while the coordinator is unreachable (every study
  // call is safe to repeat: creating and asking by request id, telling the same value again, a
  // repeated report keeps its first value).
  template <typename Request, typename Response>
  absl::Status Call(grpc::Status (v1::CoordinatorService::Stub::*method)(grpc::ClientContext*,
                                                                         const Request&, Response*),
                    const Request& request, Response& response) {
    return CallWithRetries(*stub_, method, request, response, timeout_,
                           absl::StrCat("coordinator ", address_), BackoffPolicy{},
                           [attempts = 1](const absl::Status&) mutable { return ++attempts <= 3; });
  }

  const std::string address_;
  const absl::Duration timeout_;
  std::unique_ptr<v1::CoordinatorService::Stub> stub_;
};

}  // namespace

absl::StatusOr<std::unique_ptr<StudyClient>> OpenLocalStudies(const std::string& path,
                                                              MissingStore missing) {
  if (missing == MissingStore::kRefuse && !std::filesystem::exists(path)) {
    return absl::NotFoundError(
        absl::StrCat("no study store ", path, " (dcs studies create --store makes one)"));
  }
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<coordinator::Store> store,
                       coordinator::Store::Open(path, coordinator::StoreOptions{}, absl::Now()));
  return std::make_unique<LocalStudies>(std::move(store));
}

std::unique_ptr<StudyClient> ConnectStudies(const std::string& address, absl::Duration timeout) {
  return std::make_unique<RemoteStudies>(address, timeout);
}

}  // namespace dcs::services::cli
