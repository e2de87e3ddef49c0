// Copyright 2026 The DCS Authors.
#include "services/channel.h"

#include <grpcpp/grpcpp.h>
#include <grpcpp/support/client_interceptor.h>

#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "services/auth.h"

namespace dcs::services {
namespace {

// Presents the cluster's token on every call (services/auth.h).
class TokenInterceptor final : public grpc::experimental::Interceptor {
 public:
  explicit TokenInterceptor(const std::string& token) : header_(absl::StrCat("Bearer ", token)) {}

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(
            grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA)) {
      methods->GetSendInitialMetadata()->emplace("authorization", header_);
    }
    methods->Proceed();
  }

 private:
  const std::string header_;
};

class TokenInterceptorFactory final
    : public grpc::experimental::ClientInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateClientInterceptor(
      grpc::experimental::ClientRpcInfo* /*info*/) override {
    return new TokenInterceptor(ClusterToken());
  }
};

}  // namespace

std::shared_ptr<grpc::Channel> OpenChannel(const std::string& address) {
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_KEEPALIVE_TIME_MS, 30'000);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 10'000);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2'000);
  // A sweep's results hold every run's evaluation log, about 10 KB a run without the episodes'
  // returns: gRPC's default 4 MiB stops at a few hundred runs; a sweep may have 10,000.
  args.SetMaxReceiveMessageSize(kMaxReceiveBytes);
  // gRPC's TLS checks the server's certificate against this name instead of the address.
  if (!ClusterTlsServerName().empty()) args.SetSslTargetNameOverride(ClusterTlsServerName());
  std::vector<std::unique_ptr<grpc::experimental::ClientInterceptorFactoryInterface>> token;
  if (!ClusterToken().empty()) token.push_back(std::make_unique<TokenInterceptorFactory>());
  return grpc::experimental::CreateCustomChannelWithInterceptors(
      address, ClusterChannelCredentials(), args, std::move(token));
}

void SetTimeout(grpc::ClientContext& context, absl::Duration timeout) {
  context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
}

}  // namespace dcs::services
