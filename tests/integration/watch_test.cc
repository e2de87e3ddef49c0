// Copyright 2026 The DCS Authors.
//
// Watchers on streams (issue 35, item 10), with real processes on loopback: `dcs watch`,
// `dcs runs watch` and `dcs train --cluster` follow their sweep or run on one WatchSweep or
// WatchRun stream and ask the coordinator nothing else, as its gRPC metrics count; a watch
// outlives a restart of the coordinator (it says so once and watches again); and a watcher
// that goes, detached (Ctrl-C) or killed, is released by the coordinator (dcs_watchers).

#include <signal.h>
#include <sys/wait.h>

#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/eventually.h"
#include "tests/testing/net.h"
#include "tests/testing/slowdown.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using ::dcs::testing::Eventually;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr absl::Duration kLease = absl::Seconds(1);

// The coordinator's /metrics, or "" if it does not answer.
std::string CoordinatorMetrics(const ClusterProcesses& cluster) {
  return testing::HttpGet(cluster.metrics_url("coordinator")).value_or("");
}

// How many calls of the coordinator's `method` started (grpc_server_started_total), -1 if the
// series is missing.
double CallsStarted(const std::string& metrics, const std::string& method) {
  for (const std::string& line : Lines(metrics)) {
    if (absl::StartsWith(line, "grpc_server_started_total{") &&
        absl::StrContains(line, absl::StrCat("grpc_method=\"", method, "\"")) &&
        absl::StrContains(line, "grpc_service=\"dcs.v1.CoordinatorService\"")) {
      return MetricValue(metrics, line.substr(0, line.rfind(' ')));
    }
  }
  return -1;
}

double Watchers(const ClusterProcesses& cluster, const std::string& kind) {
  return MetricValue(CoordinatorMetrics(cluster), absl::StrCat("dcs_watchers{kind=\"", kind,
                                                               "\"}"));
}

// `dcs args... --addr=<the coordinator>` started in the background, its output in `output`.
services::cli::ChildProcess StartDcs(const ClusterProcesses& cluster,
                                     std::vector<std::string> args, const std::string& output) {
  args.push_back("--addr=" + cluster.coordinator_address());
  absl::StatusOr<services::cli::ChildProcess> dcs = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs"), .args = std::move(args), .output_path = output});
  EXPECT_TRUE(dcs.ok()) << dcs.status();
  return *std::move(dcs);
}

// Writes an eight-run sweep spec of `total_timesteps` steps a run into the cluster's directory.
std::string WriteSweepSpec(const ClusterProcesses& cluster, int total_timesteps) {
  const std::string spec = cluster.dir() + "/watched.yaml";
  EXPECT_TRUE(WriteFileAtomically(
                  spec, EightRunSweepSpec("watched", total_timesteps, total_timesteps / 2))
                  .ok());
  return spec;
}

TEST(WatchTest, DcsWatchFollowsASweepToItsEndOnOneStreamAndPollsNothing) {
  ClusterProcesses cluster(kLease);
  StartCoordinatorLearnerAndActors(cluster);
  const RunResult submitted = DcsAt({"submit", WriteSweepSpec(cluster, 4096)},
                                    cluster.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  const RunResult watched = DcsAt({"watch", "sweep-1"}, cluster.coordinator_address(),
                                  testing::Patient(absl::Minutes(5)));
  ASSERT_EQ(watched.exit_code, 0) << watched.output << "; logs in " << cluster.dir();
  EXPECT_THAT(watched.output, HasSubstr("sweep-1 watched: completed, 8/8 runs done"));
  EXPECT_THAT(watched.output, Not(HasSubstr("lost the coordinator")));

  const std::string metrics = CoordinatorMetrics(cluster);
  EXPECT_EQ(CallsStarted(metrics, "WatchSweep"), 1);
  for (const char* polled : {"GetSweep", "GetRun", "ListRuns", "ListSweeps"}) {
    EXPECT_EQ(CallsStarted(metrics, polled), 0) << polled;
  }
  EXPECT_EQ(Watchers(cluster, "sweep"), 0);
}

TEST(WatchTest, AWatchOutlivesARestartOfTheCoordinatorSayingSoOnce) {
  ClusterProcesses cluster(kLease);
  cluster.StartCoordinator();  // the workers come after the restarts: the sweep waits for them
  const RunResult submitted = DcsAt({"submit", WriteSweepSpec(cluster, 4096)},
                                    cluster.coordinator_address());
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output;
  const std::string output = cluster.dir() + "/watch.out";
  services::cli::ChildProcess watch = StartDcs(cluster, {"watch", "sweep-1"}, output);
  ASSERT_TRUE(Eventually([&] { return Watchers(cluster, "sweep") == 1; }));

  // Stopped as `dcs down` stops it, it ends the watch with UNAVAILABLE; then killed.
  cluster.Stop("coordinator");
  cluster.Restart("coordinator");
  ASSERT_TRUE(Eventually([&] { return Watchers(cluster, "sweep") == 1; }))
      << ReadFile(output).value_or("") << "; logs in " << cluster.dir();
  cluster.Kill("coordinator");
  cluster.Restart("coordinator");
  cluster.StartLearner("learner");
  cluster.StartActor("actor-1", 4);

  const std::optional<int> exit = watch.Wait(testing::Patient(absl::Minutes(5)));
  const std::string shown = ReadFile(output).value_or("");
  ASSERT_TRUE(exit.has_value()) << shown << "; logs in " << cluster.dir();
  EXPECT_TRUE(WIFEXITED(*exit) && WEXITSTATUS(*exit) == 0)
      << services::cli::DescribeExit(*exit) << ": " << shown;
  EXPECT_THAT(shown, HasSubstr("sweep-1 watched: completed, 8/8 runs done"));
  // Once per outage, however many attempts it took to reach the coordinator again.
  std::vector<std::string> lost;
  for (const std::string& line : Lines(shown)) {
    if (absl::StrContains(line, "lost the coordinator")) lost.push_back(line);
  }
  ASSERT_EQ(lost.size(), 2) << shown;
  EXPECT_THAT(lost[0], HasSubstr("UNAVAILABLE: coordinator"));
  EXPECT_THAT(lost[0], HasSubstr("the coordinator is stopping"));
  EXPECT_THAT(lost[1], HasSubstr("UNAVAILABLE: coordinator"));

  const std::string metrics = CoordinatorMetrics(cluster);
  EXPECT_EQ(CallsStarted(metrics, "WatchSweep"), 1);  // since the last start
  EXPECT_EQ(CallsStarted(metrics, "GetSweep"), 0);
}

TEST(WatchTest, AWatcherThatGoesIsReleased) {
  ClusterProcesses cluster(kLease);
  cluster.StartCoordinator();  // no learner: the run stays queued
  const std::string config =
      absl::StrCat(DCS_SOURCE_DIR, "/configs/cartpole_default_static.yaml");

  // `dcs train --cluster` follows the run it submits; Ctrl-C detaches.
  services::cli::ChildProcess train =
      StartDcs(cluster, {"train", "--cluster", "--config", config, "--out", cluster.dir() + "/out"},
               cluster.dir() + "/train.out");
  ASSERT_TRUE(Eventually([&] { return Watchers(cluster, "run") == 1; }));
  ASSERT_EQ(::kill(train.pid(), SIGINT), 0);
  const std::optional<int> detached = train.Wait(testing::Patient(absl::Seconds(30)));
  ASSERT_TRUE(detached.has_value());
  EXPECT_EQ(WEXITSTATUS(*detached), 130) << services::cli::DescribeExit(*detached);
  EXPECT_TRUE(Eventually([&] { return Watchers(cluster, "run") == 0; }));

  // `dcs runs watch`, killed: its connection closes without a word.
  services::cli::ChildProcess watch =
      StartDcs(cluster, {"runs", "watch", "run-1"}, cluster.dir() + "/watch.out");
  ASSERT_TRUE(Eventually([&] { return Watchers(cluster, "run") == 1; }));
  ASSERT_EQ(::kill(watch.pid(), SIGKILL), 0);
  watch.Wait(absl::Seconds(10));
  EXPECT_TRUE(Eventually([&] { return Watchers(cluster, "run") == 0; }));

  const std::string metrics = CoordinatorMetrics(cluster);
  EXPECT_EQ(CallsStarted(metrics, "WatchRun"), 2);
  EXPECT_EQ(CallsStarted(metrics, "GetRun"), 0);
}

}  // namespace
}  // namespace dcs::integration
