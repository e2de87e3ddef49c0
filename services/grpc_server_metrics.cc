// Copyright 2026 The DCS Authors.
#include "services/grpc_server_metrics.h"

#include <google/protobuf/descriptor.h>

#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/status_util.h"

namespace dcs::services {
namespace {

using grpc::experimental::InterceptionHookPoints;
using grpc::experimental::ServerRpcInfo;

prometheus::Labels CallLabels(const GrpcServerMetrics::Call& call) {
  return {{"grpc_type", call.type}, {"grpc_service", call.service}, {"grpc_method", call.method}};
}

std::string TypeName(ServerRpcInfo::Type type) {
  switch (type) {
    case ServerRpcInfo::Type::UNARY: return "unary";
    case ServerRpcInfo::Type::CLIENT_STREAMING: return "client_stream";
    case ServerRpcInfo::Type::SERVER_STREAMING: return "server_stream";
    case ServerRpcInfo::Type::BIDI_STREAMING: return "bidi_stream";
    default: return "unknown";
  }
}

std::string TypeName(const google::protobuf::MethodDescriptor& method) {
  if (method.client_streaming()) {
    return method.server_streaming() ? "bidi_stream" : "client_stream";
  }
  return method.server_streaming() ? "server_stream" : "unary";
}

// One per call; gRPC owns it and deletes it when the call ends.
class MetricsInterceptor final : public grpc::experimental::Interceptor {
 public:
  MetricsInterceptor(GrpcServerMetrics& metrics, ServerRpcInfo* info)
      : metrics_(metrics), call_(GrpcServerMetrics::ParseCall(info->method(), TypeName(info->type()))) {}

  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_INITIAL_METADATA)) {
      start_ = absl::Now();
      metrics_.RecordStarted(call_);
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::POST_RECV_MESSAGE)) {
      metrics_.RecordMessageReceived(call_);
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_MESSAGE)) {
      metrics_.RecordMessageSent(call_);
    }
    if (methods->QueryInterceptionHookPoint(InterceptionHookPoints::PRE_SEND_STATUS)) {
      const auto code = static_cast<absl::StatusCode>(methods->GetSendStatus().error_code());
      metrics_.RecordHandled(call_, absl::StatusCodeToString(code),
                             absl::ToDoubleSeconds(absl::Now() - start_));
    }
    methods->Proceed();
  }

 private:
  GrpcServerMetrics& metrics_;
  const GrpcServerMetrics::Call call_;
  absl::Time start_ = absl::Now();
};

class MetricsInterceptorFactory final
    : public grpc::experimental::ServerInterceptorFactoryInterface {
 public:
  explicit MetricsInterceptorFactory(GrpcServerMetrics& metrics) : metrics_(metrics) {}
  grpc::experimental::Interceptor* CreateServerInterceptor(ServerRpcInfo* info) override {
    return new MetricsInterceptor(metrics_, info);
  }

 private:
  GrpcServerMetrics& metrics_;
};

}  // namespace

GrpcServerMetrics::GrpcServerMetrics(prometheus::Registry& registry)
    : started_(prometheus::BuildCounter()
                   .Name("grpc_server_started_total")
                   .Help("Total number of RPCs started on the server.")
                   .Register(registry)),
      handled_(prometheus::BuildCounter()
                   .Name("grpc_server_handled_total")
                   .Help("Total number of RPCs completed on the server, regardless of success "
                         "or failure.")
                   .Register(registry)),
      handling_seconds_(prometheus::BuildHistogram()
                            .Name("grpc_server_handling_seconds")
                            .Help("Histogram of response latency (seconds) of gRPC that had "
                                  "been application-level handled by the server.")
                            .Register(registry)),
      received_(prometheus::BuildCounter()
                    .Name("grpc_server_msg_received_total")
                    .Help("Total number of RPC stream messages received on the server.")
                    .Register(registry)),
      sent_(prometheus::BuildCounter()
                .Name("grpc_server_msg_sent_total")
                .Help("Total number of gRPC stream messages sent by the server.")
                .Register(registry)) {}

void GrpcServerMetrics::InitializeService(absl::string_view service_full_name) {
  const google::protobuf::ServiceDescriptor* service =
      google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(
          std::string(service_full_name));
  if (service == nullptr) return;
  for (int i = 0; i < service->method_count(); ++i) {
    const google::protobuf::MethodDescriptor& method = *service->method(i);
    const Call call{TypeName(method), service->full_name(), method.name()};
    started_.Add(CallLabels(call));
    prometheus::Labels handled = CallLabels(call);
    handled.emplace("grpc_code", "OK");
    handled_.Add(handled);
  }
}

std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface>
GrpcServerMetrics::NewInterceptorFactory() {
  return std::make_unique<MetricsInterceptorFactory>(*this);
}

GrpcServerMetrics::Call GrpcServerMetrics::ParseCall(absl::string_view full_method,
                                                     std::string type) {
  // "/dcs.v1.CoordinatorService/RegisterWorker"
  std::vector<absl::string_view> parts =
      absl::StrSplit(absl::StripPrefix(full_method, "/"), absl::MaxSplits('/', 1));
  Call call{std::move(type), std::string(parts[0]), ""};
  if (parts.size() == 2) call.method = std::string(parts[1]);
  return call;
}

void GrpcServerMetrics::RecordStarted(const Call& call) {
  started_.Add(CallLabels(call)).Increment();
}

void GrpcServerMetrics::RecordMessageReceived(const Call& call) {
  received_.Add(CallLabels(call)).Increment();
}

void GrpcServerMetrics::RecordMessageSent(const Call& call) {
  sent_.Add(CallLabels(call)).Increment();
}

void GrpcServerMetrics::RecordHandled(const Call& call, absl::string_view code, double seconds) {
  prometheus::Labels labels = CallLabels(call);
  handling_seconds_
      .Add(labels, prometheus::Histogram::BucketBoundaries{0.0005, 0.001, 0.0025, 0.005, 0.01,
                                                           0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5,
                                                           5, 10})
      .Observe(seconds);
  labels.emplace("grpc_code", std::string(code));
  handled_.Add(labels).Increment();
}

}  // namespace dcs::services
