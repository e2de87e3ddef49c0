// Copyright 2026 The DCS Authors.
//
// The walking skeleton end to end: dcs-coordinator, dcs-learner and dcs-actor started as real
// processes on ephemeral loopback ports (through LocalCluster, the code behind `dcs up`), each
// SERVING, the workers registered, every /metrics endpoint exporting what it should, scraped by
// a real Prometheus server, and a clean stop.

#include <memory>
#include <regex>
#include <set>
#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/cluster_client.h"
#include "services/cli/local_cluster.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using services::cli::ClusterProcess;
using services::cli::LocalCluster;
using dcs::testing::HttpGet;
using dcs::testing::MakeTempDir;
using ::testing::UnorderedElementsAre;

std::unique_ptr<LocalCluster> StartCluster() {
  absl::StatusOr<std::unique_ptr<LocalCluster>> cluster = LocalCluster::Start(
      {.data_dir = MakeTempDir(), .bin_dir = BinDir(), .actors = 1});
  EXPECT_TRUE(cluster.ok()) << cluster.status();
  return cluster.ok() ? *std::move(cluster) : nullptr;
}

// The metric families an exposition declares ("# TYPE <name> <type>").
std::set<std::string> MetricNames(const std::string& exposition) {
  std::set<std::string> names;
  static const std::regex kType("^# TYPE ([a-zA-Z_:][a-zA-Z0-9_:]*) ");
  for (const std::string& line : Lines(exposition)) {
    std::smatch match;
    if (std::regex_search(line, match, kType)) names.insert(match[1]);
  }
  return names;
}

TEST(ClusterTest, EveryProcessServesAndTheCoordinatorListsBothWorkers) {
  std::unique_ptr<LocalCluster> cluster = StartCluster();
  ASSERT_NE(cluster, nullptr);
  const services::cli::ClusterState& state = cluster->state();
  ASSERT_EQ(state.processes.size(), 3u);
  for (const ClusterProcess& process : state.processes) {
    absl::StatusOr<bool> serving =
        services::cli::IsServing(process.grpc_address, "", absl::Seconds(2));
    ASSERT_TRUE(serving.ok()) << process.name << ": " << serving.status();
    EXPECT_TRUE(*serving) << process.name;
  }
  absl::StatusOr<bool> service_serving = services::cli::IsServing(
      state.coordinator_address, "dcs.v1.CoordinatorService", absl::Seconds(2));
  EXPECT_TRUE(service_serving.ok() && *service_serving) << service_serving.status();

  absl::StatusOr<v1::GetClusterStatusResponse> status =
      services::cli::GetClusterStatus(state.coordinator_address, absl::Seconds(5));
  ASSERT_TRUE(status.ok()) << status.status();
  std::vector<std::pair<v1::WorkerRole, std::string>> workers;
  for (const v1::Worker& worker : status->workers()) {
    EXPECT_EQ(worker.state(), v1::WORKER_STATE_ALIVE) << worker.worker_id();
    workers.emplace_back(worker.info().role(), worker.info().address());
  }
  EXPECT_THAT(workers, UnorderedElementsAre(
                           std::pair(v1::WORKER_ROLE_LEARNER, state.processes[1].grpc_address),
                           std::pair(v1::WORKER_ROLE_ACTOR, state.processes[2].grpc_address)));
}

TEST(ClusterTest, EveryProcessExportsItsMetricsAndPassesPromtool) {
  std::unique_ptr<LocalCluster> cluster = StartCluster();
  ASSERT_NE(cluster, nullptr);
  const std::set<std::string> common = {
      "dcs_build_info",           "dcs_library_info",
      "process_cpu_seconds_total", "process_resident_memory_bytes",
      "process_virtual_memory_bytes", "process_start_time_seconds",
      "process_open_fds",         "process_max_fds",
      "process_threads",          "grpc_server_started_total",
      "grpc_server_handled_total", "grpc_server_handling_seconds"};
  const std::set<std::string> coordinator = {"dcs_workers", "dcs_worker_registrations_total"};
  const std::set<std::string> worker = {"dcs_coordinator_connected",
                                        "dcs_coordinator_rpc_failures_total"};

  for (const ClusterProcess& process : cluster->state().processes) {
    SCOPED_TRACE(process.name);
    absl::StatusOr<std::string> exposition =
        HttpGet(absl::StrCat("http://", process.metrics_address, "/metrics"));
    ASSERT_TRUE(exposition.ok()) << exposition.status();
    const std::set<std::string> names = MetricNames(*exposition);
    std::set<std::string> expected = common;
    expected.merge(std::set<std::string>(process.name == "coordinator" ? coordinator : worker));
    for (const std::string& name : expected) EXPECT_TRUE(names.contains(name)) << name;

    const std::string component = process.name == "coordinator" ? "coordinator"
                                  : process.name == "learner"   ? "learner"
                                                                : "actor";
    EXPECT_THAT(*exposition, ::testing::HasSubstr(absl::StrCat(
                                 "dcs_build_info{component=\"", component, "\"")));
    if (process.name == "coordinator") {
      EXPECT_THAT(*exposition,
                  ::testing::HasSubstr("dcs_workers{role=\"actor\",state=\"alive\"} 1"));
      EXPECT_THAT(*exposition,
                  ::testing::HasSubstr("dcs_workers{role=\"learner\",state=\"alive\"} 1"));
    } else {
      EXPECT_THAT(*exposition, ::testing::HasSubstr("dcs_coordinator_connected 1"));
    }

    // Prometheus's own linter: naming rules (counters end in _total, base units, ...).
    const std::string file = absl::StrCat(MakeTempDir(), "/metrics.txt");
    ASSERT_TRUE(WriteFileAtomically(file, *exposition).ok());
    const RunResult lint =
        RunProgram("/bin/sh", {"-c", absl::StrCat("promtool check metrics < ", file)});
    EXPECT_EQ(lint.exit_code, 0) << lint.output;
  }
}

TEST(ClusterTest, SigtermStopsEveryProcessCleanlyWithinFiveSeconds) {
  std::unique_ptr<LocalCluster> cluster = StartCluster();
  ASSERT_NE(cluster, nullptr);
  const services::cli::ClusterState state = cluster->state();
  const absl::Status stopped = cluster->Stop(absl::Seconds(5));
  EXPECT_TRUE(stopped.ok()) << stopped;
  for (const ClusterProcess& process : state.processes) {
    EXPECT_FALSE(services::cli::IsProcessRunning(process.pid, process.executable)) << process.name;
  }
}

}  // namespace
}  // namespace dcs::integration
