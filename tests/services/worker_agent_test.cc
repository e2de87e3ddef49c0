// Copyright 2026 The DCS Authors.
#include "services/worker_agent.h"

#include <unistd.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <prometheus/metric_family.h>
#include <prometheus/registry.h>

#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/build_info.h"
#include "services/log.h"
#include "tests/testing/eventually.h"
#include "tests/testing/in_process_coordinator.h"
#include "tests/testing/net.h"

namespace dcs::services {
namespace {

using dcs::testing::InProcessCoordinator;
using dcs::testing::RefusingPort;
using ::testing::ElementsAre;
using ::testing::IsEmpty;

// Generous: only reached if something is broken.
constexpr absl::Duration kTimeout = absl::Seconds(10);

// A serving coordinator on `listen_address` whose workers heartbeat every 50 ms; null (and a
// test failure) if it cannot start.
std::unique_ptr<InProcessCoordinator> StartCoordinator(
    const std::string& listen_address = "127.0.0.1:0") {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> coordinator = InProcessCoordinator::Start(
      {.listen_address = listen_address,
       .registry = {.heartbeat_interval = absl::Milliseconds(50),
                    .lost_after = absl::Milliseconds(200),
                    .forget_after = absl::Seconds(30)},
       .serving = true});
  EXPECT_TRUE(coordinator.ok()) << coordinator.status();
  return coordinator.ok() ? *std::move(coordinator) : nullptr;
}

// Records on_membership_change calls and lets a test wait for them.
class MembershipLog {
 public:
  std::function<void(bool)> Callback() {
    return [this](bool joined) {
      absl::MutexLock lock(&mu_);
      changes_.push_back(joined);
    };
  }

  // Waits until `count` calls reported `joined`; false on timeout.
  bool WaitFor(bool joined, int count) {
    absl::MutexLock lock(&mu_);
    const auto reached = [&]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
      return std::count(changes_.begin(), changes_.end(), joined) >= count;
    };
    return mu_.AwaitWithTimeout(absl::Condition(&reached), kTimeout);
  }

  std::vector<bool> changes() {
    absl::MutexLock lock(&mu_);
    return changes_;
  }

 private:
  absl::Mutex mu_;
  std::vector<bool> changes_ ABSL_GUARDED_BY(mu_);
};

v1::WorkerInfo ActorInfo() {
  v1::WorkerInfo worker;
  worker.set_role(v1::WORKER_ROLE_ACTOR);
  worker.set_address("127.0.0.1:7777");
  worker.set_hostname("test-host");
  worker.set_pid(::getpid());
  worker.mutable_build()->set_version(DcsVersion());
  return worker;
}

BackoffPolicy FastBackoff() {
  return {.initial = absl::Milliseconds(10),
          .multiplier = 2.0,
          .max = absl::Milliseconds(100),
          .jitter = 0.1};
}

// The single value of a family with no labels in `metrics`; -1 if absent.
double Value(prometheus::Registry& metrics, const std::string& name) {
  for (const prometheus::MetricFamily& family : metrics.Collect()) {
    if (family.name != name || family.metric.size() != 1) continue;
    return family.type == prometheus::MetricType::Counter ? family.metric[0].counter.value
                                                          : family.metric[0].gauge.value;
  }
  return -1;
}

class WorkerAgentTest : public ::testing::Test {
 protected:
  void SetUp() override { ConfigureLogging({.component = "test", .min_level = LogLevel::kError}); }

  WorkerAgentOptions Options(const std::string& coordinator_address) {
    return {.coordinator_address = coordinator_address,
            .worker = ActorInfo(),
            .rpc_timeout = absl::Seconds(2),
            .backoff = FastBackoff(),
            .on_membership_change = membership_.Callback()};
  }

  // Declared before any agent, so that it outlives them.
  prometheus::Registry metrics_;
  MembershipLog membership_;
};

TEST_F(WorkerAgentTest, JoinsHeartbeatsAndLeaves) {
  std::unique_ptr<InProcessCoordinator> coordinator = StartCoordinator();
  ASSERT_NE(coordinator, nullptr);
  WorkerAgent agent(Options(coordinator->address()), metrics_);

  ASSERT_TRUE(membership_.WaitFor(true, 1));
  std::vector<coordinator::WorkerRecord> workers = coordinator->registry().List(absl::Now());
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_EQ(workers[0].info.address, "127.0.0.1:7777");
  EXPECT_EQ(workers[0].info.role, WorkerRole::kActor);
  EXPECT_EQ(workers[0].info.hostname, "test-host");
  EXPECT_EQ(Value(metrics_, "dcs_coordinator_connected"), 1);

  // Heartbeats arrive at the coordinator's 50 ms interval, so the worker stays alive.
  const std::string id = workers[0].id;
  ASSERT_TRUE(testing::Eventually([&] {
    const auto listed = coordinator->registry().List(absl::Now());
    return listed.size() == 1 && listed[0].last_heartbeat_at > listed[0].registered_at;
  }, kTimeout));

  agent.Stop();
  EXPECT_THAT(coordinator->registry().List(absl::Now()), IsEmpty());
  EXPECT_THAT(membership_.changes(), ElementsAre(true, false));
  EXPECT_EQ(Value(metrics_, "dcs_coordinator_connected"), 0);
  EXPECT_EQ(Value(metrics_, "dcs_coordinator_rpc_failures_total"), 0);

  agent.Stop();  // idempotent
  EXPECT_THAT(membership_.changes(), ElementsAre(true, false));
}

TEST_F(WorkerAgentTest, RetriesWithBackoffWhileCoordinatorRefusesConnections) {
  RefusingPort refusing;
  ASSERT_GT(refusing.port(), 0);
  WorkerAgent agent(Options(refusing.address()), metrics_);
  ASSERT_TRUE(testing::Eventually(
      [&] { return Value(metrics_, "dcs_coordinator_rpc_failures_total") > 2; }, kTimeout));
  EXPECT_EQ(Value(metrics_, "dcs_coordinator_connected"), 0);
  agent.Stop();
  EXPECT_THAT(membership_.changes(), IsEmpty());
}

TEST_F(WorkerAgentTest, RegistersAgainAfterCoordinatorRestart) {
  std::unique_ptr<InProcessCoordinator> first = StartCoordinator();
  ASSERT_NE(first, nullptr);
  const std::string address = first->address();
  WorkerAgent agent(Options(address), metrics_);
  ASSERT_TRUE(membership_.WaitFor(true, 1));

  // The coordinator restarts on the same port with an empty registry: the agent's heartbeats
  // fail, then get NOT_FOUND, and it registers again.
  first.reset();
  std::unique_ptr<InProcessCoordinator> second = StartCoordinator(address);
  ASSERT_NE(second, nullptr);
  ASSERT_TRUE(membership_.WaitFor(true, 2)) << ::testing::PrintToString(membership_.changes());
  const std::vector<coordinator::WorkerRecord> workers = second->registry().List(absl::Now());
  ASSERT_EQ(workers.size(), 1u);
  EXPECT_EQ(workers[0].info.address, "127.0.0.1:7777");
  EXPECT_EQ(Value(metrics_, "dcs_coordinator_connected"), 1);
  // In between, the worker was out of the cluster.
  const std::vector<bool> changes = membership_.changes();
  ASSERT_GE(changes.size(), 3u);
  EXPECT_EQ(changes[0], true);
  EXPECT_EQ(changes[1], false);
  EXPECT_EQ(changes.back(), true);

  agent.Stop();
  EXPECT_THAT(second->registry().List(absl::Now()), IsEmpty());
}

TEST_F(WorkerAgentTest, DestructorStopsAndUnregisters) {
  std::unique_ptr<InProcessCoordinator> coordinator = StartCoordinator();
  ASSERT_NE(coordinator, nullptr);
  {
    WorkerAgent agent(Options(coordinator->address()), metrics_);
    ASSERT_TRUE(membership_.WaitFor(true, 1));
  }
  EXPECT_THAT(coordinator->registry().List(absl::Now()), IsEmpty());
  EXPECT_THAT(membership_.changes(), ElementsAre(true, false));
}

}  // namespace
}  // namespace dcs::services
