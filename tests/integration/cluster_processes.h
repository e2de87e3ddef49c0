// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_INTEGRATION_CLUSTER_PROCESSES_H_
#define DCS_TESTS_INTEGRATION_CLUSTER_PROCESSES_H_

// A cluster of real DCS processes on loopback for integration tests: a coordinator on a fixed
// port and data directory (so it can be killed and restarted on them), learners and actors,
// each started, killed (SIGKILL) and restarted by the test, each logging to <dir>/<name>.log.
// Every process still running is killed with the cluster. Confined to the test's thread.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "absl/time/time.h"
#include "services/cli/child_process.h"
#include "services/port_file.h"

namespace dcs::integration {

class ClusterProcesses {
 public:
  // Leases last `lease` (short, so faults are noticed quickly).
  explicit ClusterProcesses(absl::Duration lease);

  const std::string& dir() const { return dir_; }
  // The coordinator's data directory (its store, coordinator.db, and runs/), in dir(): a test
  // may put a restored store there before StartCoordinator.
  std::string data_dir() const;
  std::string coordinator_address() const;

  // The coordinator on its port and data directory (again, after Kill), with the cluster's lease
  // duration or `lease`.
  void StartCoordinator(std::optional<absl::Duration> lease = std::nullopt);
  void StartLearner(const std::string& name);
  void StartActor(const std::string& name, int max_slots);

  // Where process `name` serves gRPC and /metrics.
  std::string address(const std::string& name) const;
  std::string metrics_url(const std::string& name) const;

  // SIGKILL, and waits for it to die.
  void Kill(const std::string& name);
  // SIGTERM, as `dcs down` stops it, and waits for it to exit (SIGKILL after 10 s).
  void Stop(const std::string& name);

  // Starts process `name`, killed or stopped before, again with the same program and arguments.
  void Restart(const std::string& name);

  // The names of the processes running now, in name order.
  std::vector<std::string> Running() const;

  // Everything process `name` logged (across restarts).
  std::string Log(const std::string& name) const;

 private:
  // Starts `command` (its program, arguments and environment) as process `name`.
  void Start(const std::string& name, services::cli::ChildProcessOptions command);

  const std::string dir_;
  const absl::Duration lease_;
  const int coordinator_port_;
  std::map<std::string, services::cli::ChildProcess> processes_;
  // Every process's program, arguments and environment as first started, for Restart.
  std::map<std::string, services::cli::ChildProcessOptions> commands_;
  std::map<std::string, services::BoundPorts> ports_;
};

// Starts `cluster`'s coordinator, a learner ("learner") and two actors of 4 slots ("actor-1",
// "actor-2").
void StartCoordinatorLearnerAndActors(ClusterProcesses& cluster);

// A sweep spec of two conditions (static, a sinusoid) in two modes, two seeds: 8 CartPole
// runs of `total_timesteps` steps each, evaluated every `evaluation_freq`.
std::string EightRunSweepSpec(const std::string& name, int total_timesteps, int evaluation_freq);

// Every format's report of a finished sweep, best and last checkpoint, as `dcs report` prints
// them: two clusters that ran the same sweep to the same results give the same text.
std::string SweepReports(const ClusterProcesses& cluster, const std::string& sweep_id);

}  // namespace dcs::integration

#endif  // DCS_TESTS_INTEGRATION_CLUSTER_PROCESSES_H_
