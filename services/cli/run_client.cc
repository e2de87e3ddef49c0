// Copyright 2026 The DCS Authors.
#include "services/cli/run_client.h"

#include <grpcpp/grpcpp.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "absl/random/random.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "google/protobuf/util/message_differencer.h"
#include "run/run_checkpoint.h"
#include "services/channel.h"
#include "services/pieces.h"
#include "services/stream_call.h"
#include "services/unary_call.h"

namespace dcs::services::cli {
namespace {

namespace fs = std::filesystem;

std::unique_ptr<v1::CoordinatorService::Stub> Coordinator(const std::string& address) {
  return v1::CoordinatorService::NewStub(OpenChannel(address));
}

// Between the attempts of a submission to a coordinator that did not answer.
constexpr BackoffPolicy kSubmitBackoff{.initial = absl::Milliseconds(200),
                                       .max = absl::Seconds(1)};

// RetryTransient's keep_trying: `attempts` in all.
auto AttemptsUpTo(int attempts) {
  return [attempts, failures = 0](const absl::Status&) mutable { return ++failures < attempts; };
}

std::string Peer(const std::string& address) { return absl::StrCat("coordinator ", address); }

}  // namespace

std::string NewRequestId() {
  absl::BitGen random;
  return absl::StrFormat("%016x%016x", absl::Uniform<uint64_t>(random),
                         absl::Uniform<uint64_t>(random));
}

absl::StatusOr<v1::Run> SubmitRun(const std::string& address, const std::string& config,
                                  const std::string& config_name, std::optional<uint64_t> seed,
                                  absl::Duration timeout) {
  v1::SubmitRunRequest request;
  request.set_request_id(NewRequestId());
  request.set_config(config);
  request.set_config_name(config_name);
  if (seed.has_value()) request.set_seed(*seed);
  v1::SubmitRunResponse response;
  // The request id makes a retry safe if the first attempt was taken but not answered.
  DCS_RETURN_IF_ERROR(CallWithRetries(*Coordinator(address),
                                      &v1::CoordinatorService::Stub::SubmitRun, request, response,
                                      timeout, Peer(address), kSubmitBackoff, AttemptsUpTo(3)));
  return response.run();
}

absl::StatusOr<v1::Sweep> SubmitSweep(const std::string& address, const std::string& spec,
                                      const std::string& spec_name, const std::string& name,
                                      absl::Duration timeout) {
  v1::SubmitSweepRequest request;
  request.set_request_id(NewRequestId());
  request.set_spec(spec);
  request.set_spec_name(spec_name);
  request.set_name(name);
  v1::SubmitSweepResponse response;
  // The request id makes a retry safe if the first attempt was taken but not answered.
  DCS_RETURN_IF_ERROR(CallWithRetries(*Coordinator(address),
                                      &v1::CoordinatorService::Stub::SubmitSweep, request, response,
                                      timeout, Peer(address), kSubmitBackoff, AttemptsUpTo(3)));
  return response.sweep();
}

absl::StatusOr<v1::GetSweepResponse> GetSweep(const std::string& address,
                                              const std::string& sweep_id,
                                              absl::Duration timeout) {
  v1::GetSweepRequest request;
  request.set_sweep_id(sweep_id);
  v1::GetSweepResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::GetSweep,
                                request, response, timeout, Peer(address)));
  return response;
}

absl::StatusOr<std::vector<v1::Sweep>> ListSweeps(const std::string& address,
                                                  absl::Duration timeout) {
  v1::ListSweepsResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address),
                                &v1::CoordinatorService::Stub::ListSweeps,
                                v1::ListSweepsRequest(), response, timeout, Peer(address)));
  return std::vector<v1::Sweep>(response.sweeps().begin(), response.sweeps().end());
}

absl::StatusOr<v1::Sweep> CancelSweep(const std::string& address, const std::string& sweep_id,
                                      absl::Duration timeout) {
  v1::CancelSweepRequest request;
  request.set_sweep_id(sweep_id);
  v1::CancelSweepResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address),
                                &v1::CoordinatorService::Stub::CancelSweep, request, response,
                                timeout, Peer(address)));
  return response.sweep();
}

absl::StatusOr<v1::DeleteSweepsResponse> DeleteSweeps(const std::string& address,
                                                      const std::vector<std::string>& sweep_ids,
                                                      absl::Duration timeout) {
  v1::DeleteSweepsRequest request;
  request.mutable_sweep_ids()->Add(sweep_ids.begin(), sweep_ids.end());
  v1::DeleteSweepsResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address),
                                &v1::CoordinatorService::Stub::DeleteSweeps, request, response,
                                timeout, Peer(address)));
  return response;
}

absl::StatusOr<v1::RetrySweepResponse> RetrySweep(const std::string& address,
                                                  const std::string& sweep_id,
                                                  absl::Duration timeout) {
  v1::RetrySweepRequest request;
  request.set_sweep_id(sweep_id);
  v1::RetrySweepResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::RetrySweep,
                                request, response, timeout, Peer(address)));
  return response;
}

absl::StatusOr<v1::SweepResults> GetSweepResults(const std::string& address,
                                                 const std::string& sweep_id, bool scores_only,
                                                 absl::Duration timeout) {
  v1::GetSweepResultsRequest request;
  request.set_sweep_id(sweep_id);
  request.set_scores_only(scores_only);
  v1::SweepResults response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address),
                                &v1::CoordinatorService::Stub::GetSweepResults, request,
                                response, timeout, Peer(address)));
  return response;
}

absl::StatusOr<v1::Run> GetRun(const std::string& address, const std::string& run_id,
                               absl::Duration timeout) {
  v1::GetRunRequest request;
  request.set_run_id(run_id);
  v1::GetRunResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::GetRun,
                                request, response, timeout, Peer(address)));
  return response.run();
}

absl::StatusOr<std::vector<v1::Run>> ListRuns(const std::string& address,
                                              absl::Duration timeout) {
  v1::ListRunsResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::ListRuns,
                                v1::ListRunsRequest(), response, timeout, Peer(address)));
  return std::vector<v1::Run>(response.runs().begin(), response.runs().end());
}

absl::StatusOr<v1::Run> CancelRun(const std::string& address, const std::string& run_id,
                                  absl::Duration timeout) {
  v1::CancelRunRequest request;
  request.set_run_id(run_id);
  v1::CancelRunResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::CancelRun,
                                request, response, timeout, Peer(address)));
  return response.run();
}

absl::StatusOr<std::vector<v1::Run>> DeleteRuns(const std::string& address,
                                                const std::vector<std::string>& run_ids,
                                                absl::Duration timeout) {
  v1::DeleteRunsRequest request;
  request.mutable_run_ids()->Add(run_ids.begin(), run_ids.end());
  v1::DeleteRunsResponse response;
  DCS_RETURN_IF_ERROR(CallUnary(*Coordinator(address), &v1::CoordinatorService::Stub::DeleteRuns,
                                request, response, timeout, Peer(address)));
  return std::vector<v1::Run>(response.runs().begin(), response.runs().end());
}

absl::StatusOr<v1::Run> WatchRun(const std::string& address, const std::string& run_id,
                                 const WatchCallbacks<v1::Run>& callbacks) {
  v1::WatchRunRequest request;
  request.set_run_id(run_id);
  // A change of the run that the caller does not show (its checkpoint) is not passed on.
  std::optional<v1::Run> shown;
  DCS_ASSIGN_OR_RETURN(
      const v1::GetRunResponse ended,
      FollowWatch<v1::GetRunResponse>(
          *Coordinator(address),
          [&](v1::CoordinatorService::Stub& stub, grpc::ClientContext* context,
              grpc::CompletionQueue* queue) {
            return stub.PrepareAsyncWatchRun(context, request, queue);
          },
          {.on_update =
               [&](const v1::GetRunResponse& update) {
                 const v1::Run& run = update.run();
                 if (shown.has_value() && shown->state() == run.state() &&
                     google::protobuf::util::MessageDifferencer::Equals(shown->progress(),
                                                                        run.progress())) {
                   return;
                 }
                 shown = run;
                 callbacks.on_update(run);
               },
           .interrupted = callbacks.interrupted,
           .on_lost = callbacks.on_lost},
          Peer(address), absl::StrCat("stopped following ", run_id)));
  return ended.run();
}

absl::StatusOr<v1::GetSweepResponse> WatchSweep(
    const std::string& address, const std::string& sweep_id,
    const WatchCallbacks<v1::GetSweepResponse>& callbacks) {
  v1::WatchSweepRequest request;
  request.set_sweep_id(sweep_id);
  return FollowWatch<v1::GetSweepResponse>(
      *Coordinator(address),
      [&](v1::CoordinatorService::Stub& stub, grpc::ClientContext* context,
          grpc::CompletionQueue* queue) {
        return stub.PrepareAsyncWatchSweep(context, request, queue);
      },
      callbacks, Peer(address), absl::StrCat("stopped following ", sweep_id));
}

std::string WatchLostMessage(const absl::Status& status) {
  return absl::StrCat("dcs: lost the coordinator (", status.ToString(),
                      "); watching again once it is back");
}

absl::Status DownloadRun(const std::string& address, const std::string& run_id,
                         const std::string& dir, absl::Duration timeout) {
  v1::GetRunFilesRequest request;
  request.set_run_id(run_id);
  // Files come in pieces, each file's in order: one is written once its last piece is in.
  v1::RunFile file;
  auto write = [&]() -> absl::Status {
    const fs::path relative = fs::path(file.path()).lexically_normal();
    if (relative.is_absolute() || relative.empty() || *relative.begin() == "..") {
      return absl::InvalidArgumentError(
          absl::StrCat("the coordinator sent a file outside the run's directory: ", file.path()));
    }
    const fs::path path = fs::path(dir) / relative;
    std::error_code error;
    fs::create_directories(path.parent_path(), error);
    if (error) {
      return absl::PermissionDeniedError(
          absl::StrCat("cannot create ", path.parent_path().string(), ": ", error.message()));
    }
    return WriteFileAtomically(path.string(), file.contents());
  };
  DCS_RETURN_IF_ERROR(CallServerStream(
      *Coordinator(address), &v1::CoordinatorService::Stub::GetRunFiles, request, timeout,
      Peer(address), [&](const v1::RunFile& piece) -> absl::Status {
        if (piece.path() == file.path()) {
          file.mutable_contents()->append(piece.contents());
          return absl::OkStatus();
        }
        if (!file.path().empty()) DCS_RETURN_IF_ERROR(write());
        file = piece;
        return absl::OkStatus();
      }));
  return file.path().empty() ? absl::OkStatus() : write();
}

absl::StatusOr<v1::BackupPiece> BackupStore(const std::string& address, const std::string& out,
                                            absl::Duration timeout) {
  PieceJoiner<v1::BackupPiece> backup(&v1::BackupPiece::mutable_data, "the store's backup");
  DCS_RETURN_IF_ERROR(CallServerStream(
      *Coordinator(address), &v1::CoordinatorService::Stub::BackupStore, v1::BackupStoreRequest(),
      timeout, Peer(address),
      [&](const v1::BackupPiece& piece) { return backup.Add(piece); }));
  const std::string& bytes = backup.payload();
  if (!backup.started() || static_cast<int64_t>(bytes.size()) != backup.header().size() ||
      run::Sha256Hex(bytes) != backup.header().sha256()) {
    return absl::DataLossError(absl::StrCat(
        "the store's backup from ", Peer(address), " arrived damaged: ", bytes.size(), " of ",
        backup.header().size(), " bytes, SHA-256 ", run::Sha256Hex(bytes), " for ",
        backup.header().sha256(), "; nothing was written to ", out));
  }
  DCS_RETURN_IF_ERROR(WriteFileAtomically(out, bytes));
  return backup.header();
}

ProgressLine ProgressLineOf(const v1::RunProgress& progress) {
  ProgressLine line{.timesteps = progress.timesteps(),
                    .total_timesteps = progress.total_timesteps(),
                    .steps_per_second = progress.steps_per_second(),
                    .recent_return = progress.has_recent_return()
                                         ? progress.recent_return()
                                         : std::numeric_limits<double>::quiet_NaN()};
  if (progress.has_evaluation_step()) {
    line.evaluation_step = progress.evaluation_step();
    line.avg_combined = progress.avg_combined();
  }
  return line;
}

}  // namespace dcs::services::cli
