// Copyright 2026 The DCS Authors.
//
// dcs-coordinator: knows the cluster's workers; will assign seeds, schedules and work, run
// sweeps and collect evaluation reports.

#include <memory>

#include "absl/time/clock.h"
#include "coordinator/library_versions.h"
#include "coordinator/worker_registry.h"
#include "services/command_line.h"
#include "services/coordinator_service.h"
#include "services/service_main.h"
#include "services/worker_collector.h"

namespace dcs::services {
namespace {

class CoordinatorRole final : public ServiceRole {
 public:
  void AddFlags(CLI::App& app) override {
    AddDurationOption(app, "--heartbeat-interval", &options_.heartbeat_interval,
                      "how often workers are told to heartbeat");
    AddDurationOption(app, "--worker-timeout", &options_.lost_after,
                      "silence after which a worker is reported LOST");
    AddDurationOption(app, "--forget-after", &options_.forget_after,
                      "silence after which a LOST worker is forgotten");
  }

  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override {
    absl::StatusOr<std::unique_ptr<coordinator::WorkerRegistry>> registry =
        coordinator::WorkerRegistry::Create(options_);
    if (!registry.ok()) return registry.status();
    registry_ = *std::move(registry);
    metrics.AddCollectable(std::make_shared<WorkerCollector>(*registry_));
    service_ = std::make_unique<CoordinatorService>(*registry_, build, absl::Now(),
                                                    metrics.registry());
    return absl::OkStatus();
  }

  std::vector<ServedService> Services() override {
    return {{v1::CoordinatorService::service_full_name(), service_.get()}};
  }

  absl::Status Start(Server& server, const std::string& /*listen_address*/) override {
    server.SetServing(true);
    return absl::OkStatus();
  }

  void Stop() override {}

 private:
  coordinator::WorkerRegistryOptions options_;
  std::unique_ptr<coordinator::WorkerRegistry> registry_;
  std::unique_ptr<CoordinatorService> service_;
};

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) {
  dcs::services::CoordinatorRole role;
  return dcs::services::RunService(
      {.program = "dcs-coordinator",
       .component = "coordinator",
       .description = "dcs-coordinator: the DCS cluster's coordinator",
       .default_listen = "127.0.0.1:50051",
       .default_metrics_listen = "127.0.0.1:9464",
       .libraries = dcs::coordinator::LibraryVersions()},
      role, argc, argv);
}
