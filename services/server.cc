// Copyright 2026 The DCS Authors.
#include "services/server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>

#include <utility>

#include "absl/strings/str_cat.h"
#include "grpc/health/v1/health.pb.h"
#include "services/auth.h"
#include "services/grpc_server_metrics.h"
#include "services/log.h"

namespace dcs::services {
namespace {

// gRPC explains a failed bind in a nested error text; its os_error field is the reason a
// person needs ("Address already in use"). Falls back to the text's first clause.
std::string BindFailureReason(const std::string& grpc_errors) {
  const std::string os_error = "os_error:\"";
  if (const size_t start = grpc_errors.find(os_error); start != std::string::npos) {
    const size_t begin = start + os_error.size();
    return grpc_errors.substr(begin, grpc_errors.find('"', begin) - begin);
  }
  return grpc_errors.substr(0, grpc_errors.find(" {"));
}

}  // namespace

absl::StatusOr<std::unique_ptr<Server>> Server::Start(const ServerOptions& options) {
  std::unique_ptr<Server> server(new Server());
  server->metrics_ = std::make_unique<GrpcServerMetrics>(*options.metrics);

  grpc::EnableDefaultHealthCheckService(true);
  // The built-in health service has no protobuf descriptor of its own; linking health.proto's
  // and naming it here lets reflection clients describe grpc.health.v1.Health.
  (void)grpc::health::v1::HealthCheckRequest::descriptor();
  if (options.enable_reflection) grpc::reflection::InitProtoReflectionServerBuilderPlugin();

  grpc::ServerBuilder builder;
  // Without this, gRPC binds with SO_REUSEPORT and a second server on the same port would
  // silently share it instead of failing.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  // Accept the keepalive pings of DCS clients (services/channel.h) while they are idle.
  builder.AddChannelArgument(GRPC_ARG_KEEPALIVE_PERMIT_WITHOUT_CALLS, 1);
  builder.AddChannelArgument(GRPC_ARG_HTTP2_MIN_RECV_PING_INTERVAL_WITHOUT_DATA_MS, 10'000);
  builder.AddListeningPort(options.listen_address, ClusterServerCredentials(),
                           &server->port_);
  for (const ServedService& served : options.services) {
    builder.RegisterService(served.service);
    server->service_names_.push_back(served.full_name);
    server->metrics_->InitializeService(served.full_name);
  }
  server->metrics_->InitializeService("grpc.health.v1.Health");
  std::vector<std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>> factories;
  factories.push_back(server->metrics_->NewInterceptorFactory());
  builder.experimental().SetInterceptorCreators(std::move(factories));

  {
    GrpcLogCapture capture;
    server->server_ = builder.BuildAndStart();
    if (server->server_ == nullptr || server->port_ == 0) {
      server->server_.reset();
      return absl::UnavailableError(absl::StrCat("cannot listen on ", options.listen_address,
                                                 ": ", BindFailureReason(capture.errors())));
    }
  }
  server->SetServing(false);
  return server;
}

Server::~Server() { Shutdown(absl::ZeroDuration()); }

void Server::SetServing(bool serving) {
  if (server_ == nullptr) return;
  grpc::HealthCheckServiceInterface* health = server_->GetHealthCheckService();
  health->SetServingStatus(serving);
  for (const std::string& name : service_names_) health->SetServingStatus(name, serving);
}

void Server::Shutdown(absl::Duration grace) {
  if (server_ == nullptr) return;
  SetServing(false);
  server_->Shutdown(absl::ToChronoTime(absl::Now() + grace));
  server_->Wait();
  server_.reset();
}

}  // namespace dcs::services
