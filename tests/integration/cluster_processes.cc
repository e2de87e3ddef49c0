// Copyright 2026 The DCS Authors.
#include "tests/integration/cluster_processes.h"

#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/pinned_kernels.h"
#include "gtest/gtest.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {

ClusterProcesses::ClusterProcesses(absl::Duration lease)
    : dir_(testing::MakeTempDir()), lease_(lease), coordinator_port_(testing::PickFreePort()) {}

std::string ClusterProcesses::data_dir() const { return dir_ + "/data"; }

std::string ClusterProcesses::coordinator_address() const {
  return absl::StrCat("127.0.0.1:", coordinator_port_);
}

void ClusterProcesses::StartCoordinator(std::optional<absl::Duration> lease) {
  Start("coordinator",
        {.path = BinaryPath("dcs-coordinator"),
         .args = {absl::StrCat("--listen=", coordinator_address()), "--data-dir=" + data_dir(),
                  absl::StrCat("--lease-duration=",
                               absl::FormatDuration(lease.value_or(lease_)))}});
}

void ClusterProcesses::StartLearner(const std::string& name) {
  // With the pinned numeric kernels, as `dcs up` starts it: it starts libtorch once.
  Start(name, {.path = BinaryPath("dcs-learner"),
               .args = {"--coordinator=" + coordinator_address()},
               .environment = PinnedKernelEnvironment(environ)});
}

void ClusterProcesses::StartActor(const std::string& name, int max_slots) {
  Start(name, {.path = BinaryPath("dcs-actor"),
               .args = {"--coordinator=" + coordinator_address(),
                        absl::StrCat("--max-slots=", max_slots)}});
}

std::string ClusterProcesses::address(const std::string& name) const {
  return absl::StrCat("127.0.0.1:", ports_.at(name).grpc);
}

std::string ClusterProcesses::metrics_url(const std::string& name) const {
  return absl::StrCat("http://127.0.0.1:", ports_.at(name).metrics, "/metrics");
}

void ClusterProcesses::Kill(const std::string& name) {
  ASSERT_TRUE(processes_.count(name)) << name;
  ASSERT_EQ(::kill(processes_.at(name).pid(), SIGKILL), 0);
  processes_.at(name).Wait(absl::Seconds(10));
  processes_.erase(name);
}

void ClusterProcesses::Stop(const std::string& name) {
  ASSERT_TRUE(processes_.count(name)) << name;
  processes_.at(name).Stop(absl::Seconds(10));
  processes_.erase(name);
}

std::string ClusterProcesses::Log(const std::string& name) const {
  return ReadFile(absl::StrCat(dir_, "/", name, ".log")).value_or("");
}

void ClusterProcesses::Restart(const std::string& name) {
  ASSERT_TRUE(commands_.count(name)) << name << " was never started";
  ASSERT_FALSE(processes_.count(name)) << name << " runs";
  Start(name, commands_.at(name));
}

std::vector<std::string> ClusterProcesses::Running() const {
  std::vector<std::string> names;
  for (const auto& [name, process] : processes_) names.push_back(name);
  return names;
}

void ClusterProcesses::Start(const std::string& name, services::cli::ChildProcessOptions command) {
  commands_[name] = command;
  const std::string port_file = absl::StrCat(dir_, "/", name, ".ports");
  std::filesystem::remove(port_file);
  command.args.push_back("--port-file=" + port_file);
  command.args.push_back("--metrics-listen=127.0.0.1:0");
  command.output_path = absl::StrCat(dir_, "/", name, ".log");
  absl::StatusOr<services::cli::ChildProcess> child = services::cli::ChildProcess::Start(command);
  ASSERT_TRUE(child.ok()) << child.status();
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
  std::optional<services::BoundPorts> ports;
  while (!(ports = services::ReadPortFile(port_file)).has_value()) {
    ASSERT_LT(absl::Now(), deadline) << name << " did not start; see " << dir_;
    absl::SleepFor(absl::Milliseconds(20));
  }
  ports_[name] = *ports;
  processes_.emplace(name, *std::move(child));
}

void StartCoordinatorLearnerAndActors(ClusterProcesses& cluster) {
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  cluster.StartActor("actor-1", 4);
  cluster.StartActor("actor-2", 4);
}

std::string EightRunSweepSpec(const std::string& name, int total_timesteps, int evaluation_freq) {
  return absl::StrCat("name: ", name, R"(
seeds: 2
observe: [none, live]
env: cartpole
total_timesteps: )", total_timesteps, R"(
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: )", evaluation_freq, R"(, episodes: 2,
             contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
ppo: {n_steps: 256, batch_size: 64, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, period: 40}
    grid: {schedule.amplitude_frac: [0.5]}
)");
}

std::string SweepReports(const ClusterProcesses& cluster, const std::string& sweep_id) {
  std::string reports;
  for (const char* checkpoint : {"last", "best"}) {
    for (const char* format : {"json", "table"}) {
      const RunResult report = DcsAt(
          {"report", sweep_id, "--checkpoint", checkpoint, "--format", format},
          cluster.coordinator_address());
      EXPECT_EQ(report.exit_code, 0) << report.output;
      absl::StrAppend(&reports, report.output);
    }
  }
  return reports;
}

}  // namespace dcs::integration
