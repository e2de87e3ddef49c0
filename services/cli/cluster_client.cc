// Copyright 2026 The DCS Authors.
#include "services/cli/cluster_client.h"

#include <grpcpp/grpcpp.h>

#include <filesystem>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_util.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "common/status_macros.h"
#include "services/auth.h"
#include "services/channel.h"
#include "services/cli/local_cluster.h"
#include "services/grpc_status.h"

namespace dcs::services::cli {

std::string CoordinatorAddress(const GlobalFlags& flags) {
  if (!flags.addr.empty()) return flags.addr;
  if (absl::StatusOr<ClusterState> state = ReadClusterState(flags.data_dir); state.ok()) {
    return state->coordinator_address;
  }
  return "127.0.0.1:50051";
}

absl::StatusOr<std::string> ClientToken(const GlobalFlags& flags) {
  DCS_ASSIGN_OR_RETURN(std::string token, LoadToken(flags.token_file));
  if (!token.empty()) return token;
  const absl::StatusOr<ClusterState> local = ReadClusterState(flags.data_dir);
  const bool calls_local =
      flags.addr.empty() || (local.ok() && flags.addr == local->coordinator_address);
  const std::string local_token = TokenPath(flags.data_dir);
  if (!calls_local || !std::filesystem::exists(local_token)) return "";
  return LoadToken(local_token);
}

absl::StatusOr<bool> IsServing(const std::string& address, const std::string& service,
                               absl::Duration timeout) {
  auto stub = grpc::health::v1::Health::NewStub(OpenChannel(address));
  grpc::ClientContext context;
  SetTimeout(context, timeout);
  grpc::health::v1::HealthCheckRequest request;
  request.set_service(service);
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = stub->Check(&context, request, &response);
  if (!status.ok()) return Annotate(FromGrpcStatus(status), absl::StrCat("health of ", address));
  return response.status() == grpc::health::v1::HealthCheckResponse::SERVING;
}

absl::Status WaitUntilServing(const std::string& address, const std::string& service,
                              absl::Duration timeout) {
  const absl::Time deadline = absl::Now() + timeout;
  std::string last_answer = "no answer yet";
  while (true) {
    const absl::StatusOr<bool> serving =
        IsServing(address, service, std::min(absl::Seconds(1), timeout));
    if (serving.ok() && *serving) return absl::OkStatus();
    last_answer = serving.ok() ? "NOT_SERVING" : serving.status().ToString();
    if (absl::Now() >= deadline) break;
    absl::SleepFor(absl::Milliseconds(100));
  }
  return absl::DeadlineExceededError(absl::StrCat(address, " not SERVING after ",
                                                  absl::FormatDuration(timeout), " (last answer: ",
                                                  last_answer, ")"));
}

absl::StatusOr<v1::GetClusterStatusResponse> GetClusterStatus(const std::string& address,
                                                              absl::Duration timeout) {
  auto stub = v1::CoordinatorService::NewStub(OpenChannel(address));
  grpc::ClientContext context;
  SetTimeout(context, timeout);
  v1::GetClusterStatusResponse response;
  const grpc::Status status = stub->GetClusterStatus(&context, {}, &response);
  if (!status.ok()) {
    return Annotate(FromGrpcStatus(status), absl::StrCat("coordinator ", address));
  }
  return response;
}

}  // namespace dcs::services::cli
