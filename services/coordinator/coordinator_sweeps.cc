// Copyright 2026 The DCS Authors.
//
// CoordinatorService's sweeps: the store's sweeps (coordinator/sweep_table.h), their
// expansion from a spec (coordinator/sweep_submission.h) and their results
// (coordinator/sweep_results.h) on the wire.

#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "coordinator/run_files.h"
#include "coordinator/run_removal.h"
#include "coordinator/sweep_results.h"
#include "coordinator/sweep_submission.h"
#include "services/coordinator/coordinator_service.h"
#include "services/coordinator/record_proto.h"
#include "services/log.h"

namespace dcs::services {
namespace {

constexpr char kDefaultSpecName[] = "sweep.yaml";

}  // namespace

grpc::ServerUnaryReactor* CoordinatorService::SubmitSweep(grpc::CallbackServerContext* context,
                                                          const v1::SubmitSweepRequest* request,
                                                          v1::SubmitSweepResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    if (request->request_id().empty() && !request->validate_only()) {
      return absl::InvalidArgumentError("request_id is empty: a client names each submission");
    }
    const std::string spec_name =
        request->spec_name().empty() ? kDefaultSpecName : request->spec_name();
    DCS_ASSIGN_OR_RETURN(coordinator::ExpandedSweep sweep,
                         coordinator::ExpandSweep(request->spec(), spec_name, request->name(),
                                                  request->request_id()));
    if (request->validate_only()) {
      *response->mutable_sweep() = SweepToProto(coordinator::SweepPreview(sweep));
      return absl::OkStatus();
    }
    DCS_ASSIGN_OR_RETURN(const coordinator::SweepRecord record,
                         runs_.store->sweeps().SubmitSweep(sweep.submission, absl::Now()));
    if (sweep.study.has_value() && runs_.study_sweeps != nullptr) {
      runs_.study_sweeps->Adopt(record.id, *std::move(sweep.study));
    }
    // Each run's directory holds its config, as `dcs train` writes it (again, on a retry).
    DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::RunRecord> runs,
                         runs_.store->sweeps().ListSweepRuns(record.id));
    for (size_t i = 0; i < runs.size() && i < sweep.requests.size(); ++i) {
      run::RunRequest& run = sweep.requests[i];
      run.dir = coordinator::RunDirectory(runs_.data_dir, runs[i].id);
      DCS_RETURN_IF_ERROR(run::CreateRunDirectory(run));
    }
    Log(LogLevel::kInfo, "sweep submitted",
        {{"sweep_id", record.id}, {"name", record.name},
         {"runs", std::to_string(runs.size())}});
    *response->mutable_sweep() = SweepToProto(record);
    parked_.Wake(kRunsTopic);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetSweep(grpc::CallbackServerContext* context,
                                                       const v1::GetSweepRequest* request,
                                                       v1::GetSweepResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<v1::GetSweepResponse> sweep = ReadSweep(request->sweep_id());
    if (sweep.ok()) *response = *std::move(sweep);
    return sweep.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::ListSweeps(
    grpc::CallbackServerContext* context, const v1::ListSweepsRequest* /*request*/,
    v1::ListSweepsResponse* response) {
  return calls_.Offloaded(context, [this, response]() -> absl::Status {
    absl::StatusOr<std::vector<coordinator::SweepRecord>> sweeps =
        runs_.store->sweeps().ListSweeps();
    if (sweeps.ok()) {
      for (const coordinator::SweepRecord& sweep : *sweeps) {
        *response->add_sweeps() = SweepToProto(sweep);
      }
    }
    return sweeps.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::CancelSweep(grpc::CallbackServerContext* context,
                                                          const v1::CancelSweepRequest* request,
                                                          v1::CancelSweepResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<coordinator::SweepRecord> sweep =
        runs_.store->sweeps().CancelSweep(request->sweep_id(), absl::Now());
    if (sweep.ok()) {
      Log(LogLevel::kInfo, "sweep cancelled", {{"sweep_id", sweep->id}});
      *response->mutable_sweep() = SweepToProto(*sweep);
      RunsChanged();  // its runs, which their watches follow too
    }
    return sweep.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::RetrySweep(grpc::CallbackServerContext* context,
                                                         const v1::RetrySweepRequest* request,
                                                         v1::RetrySweepResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    absl::StatusOr<std::pair<coordinator::SweepRecord, int>> retried =
        runs_.store->sweeps().RetrySweep(request->sweep_id(), absl::Now());
    if (retried.ok()) {
      Log(LogLevel::kInfo, "sweep retried",
          {{"sweep_id", retried->first.id}, {"runs", std::to_string(retried->second)}});
      *response->mutable_sweep() = SweepToProto(retried->first);
      response->set_retried(retried->second);
      RunsChanged();  // its runs, which their watches follow too
    }
    return retried.status();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::DeleteSweeps(
    grpc::CallbackServerContext* context, const v1::DeleteSweepsRequest* request,
    v1::DeleteSweepsResponse* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    const std::vector<std::string> sweep_ids(request->sweep_ids().begin(),
                                             request->sweep_ids().end());
    DCS_ASSIGN_OR_RETURN(const coordinator::SweepRemoval removal,
                         coordinator::RemoveSweeps(*runs_.store, runs_.data_dir, sweep_ids));
    for (const coordinator::RemovedSweep& removed : removal.sweeps) {
      Log(LogLevel::kInfo, "sweep removed",
          {{"sweep_id", removed.sweep.id}, {"runs", std::to_string(removed.runs.size())}});
      *response->add_sweeps() = SweepToProto(removed.sweep);
      for (const coordinator::RunRecord& run : removed.runs) {
        *response->add_runs() = RunToProto(run);
      }
      RunsRemoved(removed.runs);
    }
    LogLeftDirectories(removal.files);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetSweepResults(
    grpc::CallbackServerContext* context, const v1::GetSweepResultsRequest* request,
    v1::SweepResults* response) {
  return calls_.Offloaded(context, [this, request, response]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const coordinator::SweepRecord sweep,
                         runs_.store->sweeps().GetSweep(request->sweep_id()));
    DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::RunRecord> runs,
                         runs_.store->sweeps().ListSweepRuns(request->sweep_id()));
    DCS_ASSIGN_OR_RETURN(*response,
                         coordinator::CollectSweepResults(sweep, runs, completed_logs_,
                                                          request->scores_only()));
    return absl::OkStatus();
  });
}

}  // namespace dcs::services
