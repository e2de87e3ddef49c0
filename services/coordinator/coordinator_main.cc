// Copyright 2026 The DCS Authors.
//
// dcs-coordinator: knows the cluster's workers, keeps runs in its data directory (a SQLite
// store and each run's files), leases runs to learners and env slots to actors, and takes back
// the leases whose holders went silent. The main builds and starts: what the coordinator does on
// its clock is coordinator/'s (the lease reaper, the study sweeps' driver), ticked here.

#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "coordinator/lease_reaper.h"
#include "coordinator/library_versions.h"
#include "coordinator/run_removal.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep_driver.h"
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
    // What a removal cut short left: nothing reads it, so a failure only costs disk space.
    const absl::StatusOr<std::vector<std::string>> leftovers =
        coordinator::RemoveLeftoverRunDirectories(*store_, runs_.data_dir);
    if (!leftovers.ok()) {
      Log(LogLevel::kWarning, "cannot remove the directories of removed runs",
          {{"error", leftovers.status().ToString()}});
    }
    for (const std::string& run_id : leftovers.value_or(std::vector<std::string>{})) {
      Log(LogLevel::kInfo, "a removed run's directory removed", {{"run_id", run_id}});
    }
    reaper_ = std::make_unique<coordinator::LeaseReaper>(*store_);
    study_logs_ = std::make_unique<coordinator::CompletedRunLogs>(runs_.data_dir);
    study_sweeps_ = std::make_unique<coordinator::StudySweepDriver>(*store_, runs_.data_dir,
                                                                    *study_logs_);
    runs_.study_sweeps = study_sweeps_.get();
    metrics.AddCollectable(std::make_shared<WorkerCollector>(*registry_));
    metrics.AddCollectable(std::make_shared<RunCollector>(*store_, runs_.data_dir));
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
    ticker_ = std::thread([this] { TickUntilStopped(); });
    server.SetServing(true);
    return absl::OkStatus();
  }

  void Stop() override {
    if (stopping_.HasBeenNotified()) return;
    service_->StopWatches();
    stopping_.Notify();
    if (ticker_.joinable()) ticker_.join();
  }

 private:
  // Ticks the lease reaper and the study sweeps' driver, at least four times a lease, until
  // Stop: lapsed leases go back to the queue without waiting for an Acquire, and study sweeps
  // ask for trials as others finish. Errors are logged; the next tick tries again. Either
  // changes runs that watches follow, so a tick that changed some wakes them.
  void TickUntilStopped() {
    const absl::Duration period = std::min(absl::Seconds(1), runs_.lease_duration / 4);
    while (!stopping_.WaitForNotificationWithTimeout(period)) {
      const absl::Time now = absl::Now();
      const coordinator::LeaseReaper::Reaped reaped = reaper_->Tick(now);
      if (!reaped.status.ok()) {
        Log(LogLevel::kError, "cannot expire leases", {{"error", reaped.status.ToString()}});
      }
      if (reaped.lapsed > 0) {
        expired_->Increment(static_cast<double>(reaped.lapsed));
        Log(LogLevel::kWarning, "leases lapsed", {{"count", std::to_string(reaped.lapsed)}});
        service_->RunsChanged();
      }
      LogStudySweeps(study_sweeps_->Tick(now));
    }
  }

  // Logs what a tick of the study sweeps' driver did, and wakes the watches if it changed runs.
  void LogStudySweeps(
      const absl::StatusOr<std::vector<coordinator::StudySweepDriver::SweepTick>>& ticks) {
    if (!ticks.ok()) {
      Log(LogLevel::kError, "cannot list study sweeps", {{"error", ticks.status().ToString()}});
      return;
    }
    for (const coordinator::StudySweepDriver::SweepTick& tick : *ticks) {
      if (!tick.step.ok()) {
        Log(LogLevel::kError, "cannot step a study sweep",
            {{"sweep_id", tick.sweep_id}, {"error", tick.step.status().ToString()}});
      } else if (tick.step->asked + tick.step->told + tick.step->retrained > 0 ||
                 tick.step->closed) {
        service_->RunsChanged();
        Log(LogLevel::kInfo, "study sweep stepped",
            {{"sweep_id", tick.sweep_id},
             {"asked", std::to_string(tick.step->asked)},
             {"told", std::to_string(tick.step->told)},
             {"retrained", std::to_string(tick.step->retrained)},
             {"closed", tick.step->closed ? "true" : "false"}});
      }
    }
  }

  coordinator::WorkerRegistryOptions options_;
  RunStorage runs_{.data_dir = "dcs-coordinator-data"};
  std::unique_ptr<coordinator::WorkerRegistry> registry_;
  std::unique_ptr<coordinator::Store> store_;
  prometheus::Counter* expired_ = nullptr;
  std::unique_ptr<coordinator::LeaseReaper> reaper_;
  std::unique_ptr<coordinator::CompletedRunLogs> study_logs_;
  std::unique_ptr<coordinator::StudySweepDriver> study_sweeps_;  // the service's too
  std::unique_ptr<CoordinatorService> service_;
  absl::Notification stopping_;
  std::thread ticker_;
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
