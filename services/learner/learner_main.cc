// Copyright 2026 The DCS Authors.
//
// dcs-learner: a cluster member that hosts runs leased from the coordinator, learns from the
// rollouts actors stream to it, and sends the coordinator progress and checkpoints
// (services/learner/).

#include <iostream>
#include <memory>
#include <thread>

#include "absl/strings/string_view.h"
#include "common/status_macros.h"
#include "common/worker_info.h"
#include "learner/torch_runtime.h"
#include "services/learner/hosted_runs.h"
#include "services/learner/learner_service.h"
#include "services/service_main.h"
#include "services/worker_role.h"

namespace dcs::services {
namespace {

class LearnerRole final : public WorkerServiceRole {
 public:
  LearnerRole() : WorkerServiceRole(WorkerRole::kLearner) {}

  void AddFlags(CLI::App& app) override {
    WorkerServiceRole::AddFlags(app);
    app.add_option("--torch-threads", torch_threads_,
                   "libtorch intra- and inter-op threads (1 keeps runs bit-for-bit "
                   "reproducible)")
        ->capture_default_str();
    app.add_option("--max-runs", max_runs_,
                   "runs hosted at once, each updating on its own thread (default: twice the "
                   "number of cores, so that some update while others' rollouts are collected)")
        ->check(CLI::PositiveNumber);
  }

  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override {
    DCS_RETURN_IF_ERROR(learner::PinTorchThreads(torch_threads_));
    DCS_RETURN_IF_ERROR(WorkerServiceRole::Init(metrics, build));
    runs_ = std::make_unique<HostedRuns>(
        HostedRunsOptions{.coordinator_address = coordinator_address(),
                          .numerics = learner::NumericFingerprint(),
                          .max_runs = max_runs_},
        metrics.registry());
    service_ = std::make_unique<LearnerService>(*runs_, metrics.registry());
    return absl::OkStatus();
  }

  std::vector<ServedService> Services() override {
    return {{v1::LearnerService::service_full_name(), service_.get()}};
  }

  absl::Status Start(Server& server, const std::string& listen_address) override {
    DCS_RETURN_IF_ERROR(WorkerServiceRole::Start(server, listen_address));
    runs_->Start(advertised_address());
    return absl::OkStatus();
  }

  void Stop() override {
    runs_->Stop();
    WorkerServiceRole::Stop();
  }

 private:
  int torch_threads_ = 1;
  int max_runs_ = static_cast<int>(2 * std::max(1u, std::thread::hardware_concurrency()));
  std::unique_ptr<HostedRuns> runs_;
  std::unique_ptr<LearnerService> service_;
};

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) {
  // Before anything else: it may run this program again with the pinned numeric kernels.
  dcs::learner::PinNumericKernels(
      [](absl::string_view note) { std::cerr << "dcs-learner: " << note << std::endl; });
  dcs::services::LearnerRole role;
  return dcs::services::RunService({.program = "dcs-learner",
                                    .component = "learner",
                                    .description = "dcs-learner: a DCS PPO learner",
                                    .default_listen = "127.0.0.1:0",
                                    .default_metrics_listen = "127.0.0.1:0",
                                    .libraries = dcs::learner::LibraryVersions()},
                                   role, argc, argv);
}
