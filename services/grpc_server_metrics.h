// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_GRPC_SERVER_METRICS_H_
#define DCS_SERVICES_GRPC_SERVER_METRICS_H_

// RPC metrics for a gRPC server, under go-grpc-prometheus's names so that stock dashboards fit
// (gRPC 1.51 has no Prometheus plugin):
//   grpc_server_started_total{grpc_type, grpc_service, grpc_method}
//   grpc_server_handled_total{grpc_type, grpc_service, grpc_method, grpc_code}
//   grpc_server_handling_seconds{grpc_type, grpc_service, grpc_method}   (histogram)
//   grpc_server_msg_received_total{...}, grpc_server_msg_sent_total{...}
// Thread-safe. Borrows the registry, which must outlive the server.

#include <memory>
#include <string>
#include "absl/strings/string_view.h"

#include <grpcpp/support/server_interceptor.h>
#include <prometheus/counter.h>
#include <prometheus/family.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

namespace dcs::services {

class GrpcServerMetrics {
 public:
  explicit GrpcServerMetrics(prometheus::Registry& registry);

  // Creates every method's started and handled{OK} series at zero, so that rate() sees the
  // first calls. `service_full_name` must be a service in the generated descriptor pool.
  void InitializeService(absl::string_view service_full_name);

  // An interceptor factory for grpc::ServerBuilder; borrows this object.
  std::unique_ptr<grpc::experimental::ServerInterceptorFactoryInterface> NewInterceptorFactory();

  // Records one event of a call, by its full method name ("/pkg.Service/Method").
  struct Call {
    std::string type;  // "unary", "client_stream", "server_stream", "bidi_stream"
    std::string service;
    std::string method;
  };
  static Call ParseCall(absl::string_view full_method, std::string type);
  void RecordStarted(const Call& call);
  void RecordMessageReceived(const Call& call);
  void RecordMessageSent(const Call& call);
  void RecordHandled(const Call& call, absl::string_view code, double seconds);

 private:
  prometheus::Family<prometheus::Counter>& started_;
  prometheus::Family<prometheus::Counter>& handled_;
  prometheus::Family<prometheus::Histogram>& handling_seconds_;
  prometheus::Family<prometheus::Counter>& received_;
  prometheus::Family<prometheus::Counter>& sent_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_GRPC_SERVER_METRICS_H_
