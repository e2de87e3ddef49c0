// Copyright 2026 The DCS Authors.
//
// dcs-actor: a stateless cluster member that steps env slots leased from the coordinator and
// streams their rollouts to the runs' learners, and runs the runs' evaluation jobs
// (services/actor/).

#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/synchronization/mutex.h"
#include "common/status_macros.h"
#include "common/worker_info.h"
#include "env/library_versions.h"
#include "services/actor/evaluation_worker.h"
#include "services/actor/slot_workers.h"
#include "services/service_main.h"
#include "services/worker_role.h"

namespace dcs::services {
namespace {

// What an actor computes with: the environments' physics and the policy's Eigen inference.
std::string ActorNumerics() {
  std::vector<std::string> parts;
  for (const LibraryVersion& library : env::LibraryVersions()) {
    parts.push_back(absl::StrCat(library.name, " ", library.version));
  }
  return absl::StrJoin(parts, ", ");
}

class ActorRole final : public WorkerServiceRole {
 public:
  ActorRole() : WorkerServiceRole(WorkerRole::kActor) {}

  void AddFlags(CLI::App& app) override {
    WorkerServiceRole::AddFlags(app);
    app.add_option("--max-slots", max_slots_,
                   "env slots held at once (of any runs; they take turns on one core)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  }

  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override {
    DCS_RETURN_IF_ERROR(WorkerServiceRole::Init(metrics, build));
    metrics_ = &metrics.registry();
    return absl::OkStatus();
  }

  absl::Status Start(Server& server, const std::string& listen_address) override {
    DCS_RETURN_IF_ERROR(WorkerServiceRole::Start(server, listen_address));
    const std::string holder = absl::StrCat("actor@", advertised_address());
    const std::string numerics = ActorNumerics();
    slots_ = std::make_unique<SlotWorkers>(
        SlotWorkersOptions{.coordinator_address = coordinator_address(),
                           .holder = holder,
                           .numerics = numerics,
                           .max_slots = max_slots_},
        *metrics_, core_);
    evaluations_ = std::make_unique<EvaluationWorker>(
        EvaluationWorkerOptions{.coordinator_address = coordinator_address(),
                                .holder = holder,
                                .numerics = numerics},
        *metrics_, core_);
    return absl::OkStatus();
  }

  void Stop() override {
    if (slots_ != nullptr) slots_->Stop();
    if (evaluations_ != nullptr) evaluations_->Stop();
    WorkerServiceRole::Stop();
  }

 private:
  int max_slots_ = 64;
  prometheus::Registry* metrics_ = nullptr;
  absl::Mutex core_;  // the one core the actor computes on: a slot steps or a job evaluates
  std::unique_ptr<SlotWorkers> slots_;
  std::unique_ptr<EvaluationWorker> evaluations_;
};

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) {
  dcs::services::ActorRole role;
  return dcs::services::RunService({.program = "dcs-actor",
                                    .component = "actor",
                                    .description = "dcs-actor: a DCS environment actor",
                                    .default_listen = "127.0.0.1:0",
                                    .default_metrics_listen = "127.0.0.1:0",
                                    .libraries = dcs::env::LibraryVersions()},
                                   role, argc, argv);
}
