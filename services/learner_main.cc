// Copyright 2026 The DCS Authors.
//
// dcs-learner: a cluster member that will run PPO updates on the trajectories actors stream
// to it.

#include <iostream>

#include "absl/strings/string_view.h"
#include "common/status_macros.h"
#include "coordinator/worker_registry.h"
#include "learner/torch_runtime.h"
#include "services/service_main.h"
#include "services/worker_role.h"

namespace dcs::services {
namespace {

class LearnerRole final : public WorkerServiceRole {
 public:
  LearnerRole() : WorkerServiceRole(coordinator::WorkerRole::kLearner) {}

  void AddFlags(CLI::App& app) override {
    WorkerServiceRole::AddFlags(app);
    app.add_option("--torch-threads", torch_threads_,
                   "libtorch intra- and inter-op threads (1 keeps runs bit-for-bit "
                   "reproducible)")
        ->capture_default_str();
  }

  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override {
    DCS_RETURN_IF_ERROR(learner::PinTorchThreads(torch_threads_));
    return WorkerServiceRole::Init(metrics, build);
  }

 private:
  int torch_threads_ = 1;
};

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) {
  // Before anything else: it may run this program again with other numeric kernels.
  dcs::learner::RestartWithBestBlasKernels(
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
