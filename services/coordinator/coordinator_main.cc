// Copyright 2026 The DCS Authors.
//
// dcs-coordinator: knows the cluster's workers, keeps runs in its data directory (a SQLite
// store and each run's files), leases runs to learners and env slots to actors, and takes back
// the leases whose holders went silent.

#include <filesystem>
#include <memory>
#include <thread>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "coordinator/library_versions.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep.h"
#include "coordinator/sweep_results.h"
#include "coordinator/worker_registry.h"
#include "services/command_line.h"
#include "services/coordinator/coordinator_service.h"
#include "services/log.h"
#include "services/coordinator/run_collector.h"
#include "services/service_main.h"
#include "services/coordinator/worker_collector.h"

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
    app.add_option("--data-dir", runs_.data_dir,
                   "where runs are kept: coordinator.db (SQLite) and runs/<run id>/")
        ->capture_default_str();
    AddDurationOption(app, "--lease-duration", &runs_.lease_duration,
                      "how long a lease lasts unless renewed; a learner or actor silent this "
                      "long loses its work to another");
    app.add_option("--keep-checkpoints", runs_.keep_checkpoints,
                   "checkpoints kept per run (the newest)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
  }

  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override {
    absl::StatusOr<std::unique_ptr<coordinator::WorkerRegistry>> registry =
        coordinator::WorkerRegistry::Create(options_);
    if (!registry.ok()) return registry.status();
    registry_ = *std::move(registry);
    std::error_code error;
    std::filesystem::create_directories(runs_.data_dir, error);
    if (error) {
      return absl::PermissionDeniedError(
          absl::StrCat("cannot create the data directory ", runs_.data_dir, ": ",
                       error.message()));
    }
    DCS_ASSIGN_OR_RETURN(store_,
                         coordinator::Store::Open(
                             (std::filesystem::path(runs_.data_dir) / "coordinator.db").string(),
                             {.lease_duration = runs_.lease_duration}, absl::Now()));
    runs_.store = store_.get();
    study_logs_ = std::make_unique<coordinator::CompletedRunLogs>(runs_.data_dir);
    metrics.AddCollectable(std::make_shared<WorkerCollector>(*registry_));
    metrics.AddCollectable(std::make_shared<RunCollector>(*store_));
    expired_ = &prometheus::BuildCounter()
                    .Name("dcs_leases_expired_total")
                    .Help("Leases that lapsed (their holders stopped renewing) and went back to "
                          "the queue.")
                    .Register(metrics.registry())
                    .Add({});
    service_ = std::make_unique<CoordinatorService>(*registry_, runs_, build, absl::Now(),
                                                    metrics.registry());
    return absl::OkStatus();
  }

  std::vector<ServedService> Services() override {
    return {{v1::CoordinatorService::service_full_name(), service_.get()}};
  }

  absl::Status Start(Server& server, const std::string& /*listen_address*/) override {
    reaper_ = std::thread([this] { ReapLapsedLeases(); });
    server.SetServing(true);
    return absl::OkStatus();
  }

  void Stop() override {
    if (stopping_.HasBeenNotified()) return;
    service_->StopWatches();
    stopping_.Notify();
    if (reaper_.joinable()) reaper_.join();
  }

 private:
  // Returns lapsed leases to the queue as they lapse (every Acquire does too, but queue depths
  // and run states should not wait for one), and steps the open study sweeps.
  // Counts and logs every lapse, including those an Acquire expired first: under load the
  // workers' Acquire calls find nearly all of them. Either changes runs that watches follow.
  void ReapLapsedLeases() {
    const absl::Duration period = std::min(absl::Seconds(1), runs_.lease_duration / 4);
    int64_t reported = store_->LeasesLapsed();
    while (!stopping_.WaitForNotificationWithTimeout(period)) {
      absl::StatusOr<int> expired = store_->ExpireLeases(absl::Now());
      if (!expired.ok()) {
        Log(LogLevel::kError, "cannot expire leases", {{"error", expired.status().ToString()}});
      }
      const int64_t lapsed = store_->LeasesLapsed();
      if (lapsed > reported) {
        expired_->Increment(static_cast<double>(lapsed - reported));
        Log(LogLevel::kWarning, "leases lapsed", {{"count", std::to_string(lapsed - reported)}});
        reported = lapsed;
        service_->RunsChanged();
      }
      AdvanceStudySweeps();
    }
  }

  // One step of each open study sweep (coordinator/study_sweep.h). A sweep whose step fails is
  // logged and tried again at the next.
  void AdvanceStudySweeps() {
    absl::StatusOr<std::vector<coordinator::SweepRecord>> sweeps =
        store_->sweeps().ListOpenSweeps();
    if (!sweeps.ok()) {
      Log(LogLevel::kError, "cannot list study sweeps", {{"error", sweeps.status().ToString()}});
      return;
    }
    for (const coordinator::SweepRecord& sweep : *sweeps) {
      auto spec = study_specs_.find(sweep.id);
      if (spec == study_specs_.end()) {  // checked when it was submitted
        absl::StatusOr<coordinator::StudySweepSpec> parsed =
            coordinator::ParseStudySweepYaml(sweep.spec, sweep.name);
        if (!parsed.ok()) {
          Log(LogLevel::kError, "cannot read a study sweep's spec",
              {{"sweep_id", sweep.id}, {"error", parsed.status().ToString()}});
          continue;
        }
        spec = study_specs_.emplace(sweep.id, *std::move(parsed)).first;
      }
      absl::StatusOr<coordinator::StudySweepStep> step = coordinator::AdvanceStudySweep(
          *store_, runs_.data_dir, *study_logs_, sweep, spec->second, absl::Now());
      if (!step.ok()) {
        Log(LogLevel::kError, "cannot step a study sweep",
            {{"sweep_id", sweep.id}, {"error", step.status().ToString()}});
      } else if (step->asked + step->told + step->retrained > 0 || step->closed) {
        service_->RunsChanged();
        Log(LogLevel::kInfo, "study sweep stepped",
            {{"sweep_id", sweep.id},
             {"asked", std::to_string(step->asked)},
             {"told", std::to_string(step->told)},
             {"retrained", std::to_string(step->retrained)},
             {"closed", step->closed ? "true" : "false"}});
      }
      if (step.ok() && step->closed) study_specs_.erase(spec);
    }
  }

  coordinator::WorkerRegistryOptions options_;
  RunStorage runs_{.data_dir = "dcs-coordinator-data"};
  std::unique_ptr<coordinator::WorkerRegistry> registry_;
  std::unique_ptr<coordinator::Store> store_;
  prometheus::Counter* expired_ = nullptr;
  std::unique_ptr<CoordinatorService> service_;
  // The reaper's: the open study sweeps' specs, parsed once, and their completed runs' logs.
  absl::flat_hash_map<std::string, coordinator::StudySweepSpec> study_specs_;
  std::unique_ptr<coordinator::CompletedRunLogs> study_logs_;
  absl::Notification stopping_;
  std::thread reaper_;
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
