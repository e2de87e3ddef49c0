// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_IN_PROCESS_COORDINATOR_H_
#define DCS_TESTS_TESTING_IN_PROCESS_COORDINATOR_H_

// A coordinator served inside the test process: a WorkerRegistry, a Store in a data
// directory, the CoordinatorService over them, and a services::Server serving that service,
// with its metrics in a prometheus::Registry.
// For tests of code that talks to a coordinator over gRPC. Thread-compatible.

#include <memory>
#include <optional>
#include <string>

#include <prometheus/registry.h>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "coordinator/worker_registry.h"
#include "services/build_info.h"
#include "services/coordinator/coordinator_service.h"
#include "services/server.h"

namespace dcs::testing {

struct InProcessCoordinatorOptions {
  // host:port; port 0 picks a free port. Give an earlier address() to restart on its port.
  std::string listen_address = "127.0.0.1:0";
  coordinator::WorkerRegistryOptions registry;
  services::BuildInfo build = services::ProcessBuildInfo({});
  std::optional<absl::Time> start_time;  // absl::Now() if unset
  bool serving = false;                  // SetServing(true) once started
  std::string data_dir;                  // a new temporary directory if empty
  absl::Duration lease_duration = absl::Seconds(10);
};

class InProcessCoordinator {
 public:
  // The registry's status if its options are invalid; the server's if it cannot listen.
  static absl::StatusOr<std::unique_ptr<InProcessCoordinator>> Start(
      const InProcessCoordinatorOptions& options = {});
  // Shuts the server down with no grace period.
  ~InProcessCoordinator();

  InProcessCoordinator(const InProcessCoordinator&) = delete;
  InProcessCoordinator& operator=(const InProcessCoordinator&) = delete;

  // "127.0.0.1:<port>": where clients reach the server.
  std::string address() const;
  coordinator::WorkerRegistry& registry() { return *registry_; }
  // grpc_server_* and dcs_worker_registrations_total; shared, to add to a MetricsEndpoint.
  const std::shared_ptr<prometheus::Registry>& metrics() const { return metrics_; }
  services::Server& server() { return *server_; }

 private:
  InProcessCoordinator() = default;

  // Destroyed bottom-up: the server before the service, registry and metrics it uses.
  std::shared_ptr<prometheus::Registry> metrics_ = std::make_shared<prometheus::Registry>();
  std::unique_ptr<coordinator::WorkerRegistry> registry_;
  std::unique_ptr<coordinator::Store> store_;
  std::unique_ptr<services::CoordinatorService> service_;
  std::unique_ptr<services::Server> server_;
};

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_IN_PROCESS_COORDINATOR_H_
