// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_SERVER_H_
#define DCS_SERVICES_SERVER_H_

// The gRPC server of a DCS process, as a handle: Start() listens and serves the given services
// plus the standard health service (grpc.health.v1) and, when asked, server reflection
// (grpc.reflection.v1alpha, the only version gRPC 1.51 has); port() is the bound port;
// Shutdown() drains. Thread-safe. The destructor shuts down with no grace period.
//
// Health: the whole server ("") and every named service start NOT_SERVING; the process says
// when it is ready with SetServing(true), and Shutdown() sets NOT_SERVING before draining so
// that probes stop sending traffic first.

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"

namespace grpc {
class Server;
class Service;
}  // namespace grpc

namespace prometheus {
class Registry;
}

namespace dcs::services {

class GrpcServerMetrics;

struct ServedService {
  std::string full_name;   // e.g. "dcs.v1.CoordinatorService", for health and metrics
  grpc::Service* service;  // borrowed; must outlive the server
};

struct ServerOptions {
  std::string listen_address;  // host:port; port 0 picks a free port
  std::vector<ServedService> services;
  bool enable_reflection = false;
  prometheus::Registry* metrics = nullptr;  // borrowed; receives grpc_server_* metrics
};

class Server {
 public:
  // UNAVAILABLE, with the address and gRPC's reason, if the address cannot be bound.
  // REQUIRES: options.metrics != nullptr.
  static absl::StatusOr<std::unique_ptr<Server>> Start(const ServerOptions& options);
  ~Server();

  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int port() const { return port_; }

  // Sets the health of the whole server and of every served service.
  void SetServing(bool serving);

  // Marks the server NOT_SERVING, then stops it: calls still running after `grace` are
  // cancelled. Idempotent.
  void Shutdown(absl::Duration grace);

 private:
  Server() = default;

  std::unique_ptr<GrpcServerMetrics> metrics_;
  std::vector<std::string> service_names_;
  std::unique_ptr<grpc::Server> server_;
  int port_ = 0;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_SERVER_H_
