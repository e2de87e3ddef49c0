// Copyright 2026 The DCS Authors.
#include "coordinator/worker_registry.h"

#include <set>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::StartsWith;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);

WorkerRegistryOptions TestOptions() {
  return {.heartbeat_interval = absl::Seconds(1),
          .lost_after = absl::Seconds(5),
          .forget_after = absl::Seconds(60)};
}

std::unique_ptr<WorkerRegistry> NewRegistry(WorkerRegistryOptions options = TestOptions()) {
  absl::StatusOr<std::unique_ptr<WorkerRegistry>> registry = WorkerRegistry::Create(options);
  EXPECT_TRUE(registry.ok()) << registry.status();
  return registry.ok() ? *std::move(registry) : nullptr;
}

WorkerInfo Info(WorkerRole role, std::string address) {
  return {.role = role,
          .address = std::move(address),
          .hostname = "host-a",
          .pid = 4242,
          .version = "0.1.0+abc1234",
          .libraries = {{"sqlite", "3.40.1"}}};
}

std::string MustRegister(WorkerRegistry& registry, WorkerRole role, absl::Time now,
                         std::string address = "127.0.0.1:1000") {
  absl::StatusOr<std::string> id = registry.Register(Info(role, std::move(address)), now);
  EXPECT_TRUE(id.ok()) << id.status();
  return id.value_or("");
}

std::vector<std::string> Ids(const std::vector<WorkerRecord>& records) {
  std::vector<std::string> ids;
  for (const WorkerRecord& record : records) ids.push_back(record.id);
  return ids;
}

TEST(WorkerRegistryCreateTest, AcceptsValidOptions) {
  EXPECT_TRUE(WorkerRegistry::Create(TestOptions()).ok());
  // The boundaries themselves: lost_after == 2 * heartbeat_interval is allowed.
  EXPECT_TRUE(WorkerRegistry::Create({.heartbeat_interval = absl::Seconds(1),
                                      .lost_after = absl::Seconds(2),
                                      .forget_after = absl::Seconds(3)})
                  .ok());
}

TEST(WorkerRegistryCreateTest, RejectsNonPositiveHeartbeatInterval) {
  for (absl::Duration interval : {absl::ZeroDuration(), absl::Seconds(-1)}) {
    WorkerRegistryOptions options = TestOptions();
    options.heartbeat_interval = interval;
    EXPECT_EQ(WorkerRegistry::Create(options).status().code(), absl::StatusCode::kInvalidArgument)
        << interval;
  }
}

TEST(WorkerRegistryCreateTest, RejectsLostAfterBelowTwoHeartbeats) {
  WorkerRegistryOptions options = TestOptions();
  options.lost_after = 2 * options.heartbeat_interval - absl::Milliseconds(1);
  EXPECT_EQ(WorkerRegistry::Create(options).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(WorkerRegistryCreateTest, RejectsForgetAfterNotAboveLostAfter) {
  WorkerRegistryOptions options = TestOptions();
  options.forget_after = options.lost_after;
  EXPECT_EQ(WorkerRegistry::Create(options).status().code(), absl::StatusCode::kInvalidArgument);
  options.forget_after = options.lost_after - absl::Seconds(1);
  EXPECT_EQ(WorkerRegistry::Create(options).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(WorkerRegistryCreateTest, KeepsOptions) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  EXPECT_EQ(registry->options().heartbeat_interval, absl::Seconds(1));
  EXPECT_EQ(registry->options().lost_after, absl::Seconds(5));
  EXPECT_EQ(registry->options().forget_after, absl::Seconds(60));
}

TEST(WorkerRegistryTest, IdsAreRoleAndNumber) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string first = MustRegister(*registry, WorkerRole::kActor, kStart);
  const std::string second = MustRegister(*registry, WorkerRole::kLearner, kStart);
  const std::string third = MustRegister(*registry, WorkerRole::kActor, kStart);
  EXPECT_THAT(first, StartsWith("actor-"));
  EXPECT_THAT(second, StartsWith("learner-"));
  EXPECT_THAT(third, StartsWith("actor-"));
  for (const std::string& id : {first, second, third}) {
    const std::string number = id.substr(id.find('-') + 1);
    ASSERT_FALSE(number.empty()) << id;
    EXPECT_EQ(number.find_first_not_of("0123456789"), std::string::npos) << id;
  }
  EXPECT_EQ(std::set<std::string>({first, second, third}).size(), 3u);
}

TEST(WorkerRegistryTest, RegisteredWorkerIsListedWithItsInfo) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string id = MustRegister(*registry, WorkerRole::kLearner, kStart, "10.0.0.7:5000");
  const std::vector<WorkerRecord> records = registry->List(kStart + absl::Seconds(1));
  ASSERT_EQ(records.size(), 1u);
  const WorkerRecord& record = records[0];
  EXPECT_EQ(record.id, id);
  EXPECT_EQ(record.info.role, WorkerRole::kLearner);
  EXPECT_EQ(record.info.address, "10.0.0.7:5000");
  EXPECT_EQ(record.info.hostname, "host-a");
  EXPECT_EQ(record.info.pid, 4242);
  EXPECT_EQ(record.info.version, "0.1.0+abc1234");
  EXPECT_THAT(record.info.libraries, ElementsAre(LibraryVersion{"sqlite", "3.40.1"}));
  EXPECT_EQ(record.state, WorkerState::kAlive);
  EXPECT_EQ(record.registered_at, kStart);
  EXPECT_EQ(record.last_heartbeat_at, kStart);
}

TEST(WorkerRegistryTest, EmptyAddressIsRejected) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  EXPECT_EQ(registry->Register(Info(WorkerRole::kActor, ""), kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(registry->List(kStart), IsEmpty());
}

TEST(WorkerRegistryTest, HeartbeatOfUnknownIdIsNotFound) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  EXPECT_EQ(registry->Heartbeat("actor-1", kStart).code(), absl::StatusCode::kNotFound);
  MustRegister(*registry, WorkerRole::kActor, kStart);
  EXPECT_EQ(registry->Heartbeat("actor-999", kStart).code(), absl::StatusCode::kNotFound);
}

TEST(WorkerRegistryTest, HeartbeatUpdatesLastHeartbeatTime) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string id = MustRegister(*registry, WorkerRole::kActor, kStart);
  const absl::Time later = kStart + absl::Seconds(3);
  ASSERT_TRUE(registry->Heartbeat(id, later).ok());
  const std::vector<WorkerRecord> records = registry->List(later);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].registered_at, kStart);
  EXPECT_EQ(records[0].last_heartbeat_at, later);
}

TEST(WorkerRegistryTest, WorkerIsLostExactlyAtLostAfterAndRevivedByHeartbeat) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string id = MustRegister(*registry, WorkerRole::kActor, kStart);
  const absl::Duration lost_after = registry->options().lost_after;

  std::vector<WorkerRecord> records = registry->List(kStart + lost_after - absl::Nanoseconds(1));
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].state, WorkerState::kAlive);

  records = registry->List(kStart + lost_after);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].state, WorkerState::kLost);

  const absl::Time revived = kStart + lost_after + absl::Seconds(10);
  ASSERT_TRUE(registry->Heartbeat(id, revived).ok());
  records = registry->List(revived);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].id, id);
  EXPECT_EQ(records[0].state, WorkerState::kAlive);
  // And it is lost again only after another full lost_after of silence.
  EXPECT_EQ(registry->List(revived + lost_after - absl::Nanoseconds(1))[0].state,
            WorkerState::kAlive);
  EXPECT_EQ(registry->List(revived + lost_after)[0].state, WorkerState::kLost);
}

TEST(WorkerRegistryTest, HeartbeatsKeepWorkerAlivePastLostAfter) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string id = MustRegister(*registry, WorkerRole::kActor, kStart);
  absl::Time now = kStart;
  for (int i = 0; i < 20; ++i) {
    now += registry->options().heartbeat_interval;
    ASSERT_TRUE(registry->Heartbeat(id, now).ok());
  }
  ASSERT_GT(now - kStart, registry->options().lost_after);
  const std::vector<WorkerRecord> records = registry->List(now);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].state, WorkerState::kAlive);
}

TEST(WorkerRegistryTest, SilentWorkerIsForgottenAfterForgetAfter) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string id = MustRegister(*registry, WorkerRole::kActor, kStart);
  const absl::Duration forget_after = registry->options().forget_after;

  const std::vector<WorkerRecord> just_before =
      registry->List(kStart + forget_after - absl::Nanoseconds(1));
  ASSERT_EQ(just_before.size(), 1u);
  EXPECT_EQ(just_before[0].state, WorkerState::kLost);

  EXPECT_THAT(registry->List(kStart + forget_after), IsEmpty());
  EXPECT_EQ(registry->Heartbeat(id, kStart + forget_after).code(), absl::StatusCode::kNotFound);
}

TEST(WorkerRegistryTest, ForgettingOneWorkerKeepsTheOthers) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string silent = MustRegister(*registry, WorkerRole::kActor, kStart);
  const absl::Time later = kStart + absl::Seconds(30);
  const std::string fresh = MustRegister(*registry, WorkerRole::kActor, later);
  const absl::Time forget_silent = kStart + registry->options().forget_after;
  EXPECT_THAT(Ids(registry->List(forget_silent)), ElementsAre(fresh));
  EXPECT_TRUE(registry->Heartbeat(fresh, forget_silent).ok());
  EXPECT_EQ(registry->Heartbeat(silent, forget_silent).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(registry->Unregister(silent, forget_silent).code(), absl::StatusCode::kNotFound);
}

TEST(WorkerRegistryTest, UnregisterRemovesAndSecondUnregisterIsNotFound) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string leaving = MustRegister(*registry, WorkerRole::kActor, kStart);
  const std::string staying = MustRegister(*registry, WorkerRole::kActor, kStart);
  ASSERT_TRUE(registry->Unregister(leaving, kStart).ok());
  EXPECT_THAT(Ids(registry->List(kStart)), ElementsAre(staying));
  EXPECT_EQ(registry->Unregister(leaving, kStart).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(registry->Heartbeat(leaving, kStart).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(registry->Unregister("learner-77", kStart).code(), absl::StatusCode::kNotFound);
}

TEST(WorkerRegistryTest, ReRegistrationGetsANewId) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  const std::string first = MustRegister(*registry, WorkerRole::kLearner, kStart);
  ASSERT_TRUE(registry->Unregister(first, kStart).ok());
  const std::string second = MustRegister(*registry, WorkerRole::kLearner, kStart);
  EXPECT_NE(first, second);
}

TEST(WorkerRegistryTest, ListsLearnersFirstThenInRegistrationOrder) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  std::vector<std::string> actors;
  std::vector<std::string> learners;
  // Enough actors that ids reach two digits, so lexicographic and registration order differ.
  for (int i = 0; i < 12; ++i) {
    actors.push_back(MustRegister(*registry, WorkerRole::kActor, kStart));
    if (i % 5 == 0) learners.push_back(MustRegister(*registry, WorkerRole::kLearner, kStart));
  }
  std::vector<std::string> expected = learners;
  expected.insert(expected.end(), actors.begin(), actors.end());
  EXPECT_EQ(Ids(registry->List(kStart)), expected);
}

TEST(WorkerRegistryTest, ConcurrentRegistrationsGetUniqueIds) {
  auto registry = NewRegistry();
  ASSERT_NE(registry, nullptr);
  constexpr int kThreads = 8;
  constexpr int kPerThread = 200;
  absl::Mutex mu;
  std::vector<std::string> ids;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      const WorkerRole role = t % 2 == 0 ? WorkerRole::kActor : WorkerRole::kLearner;
      std::vector<std::string> mine;
      for (int i = 0; i < kPerThread; ++i) {
        absl::StatusOr<std::string> id = registry->Register(Info(role, "127.0.0.1:1"), kStart);
        mine.push_back(id.ok() ? *id : "error: " + id.status().ToString());
        // Interleave reads and heartbeats with the writes.
        if (i % 16 == 0) (void)registry->List(kStart);
        if (id.ok() && i % 7 == 0) (void)registry->Heartbeat(*id, kStart);
      }
      absl::MutexLock lock(&mu);
      ids.insert(ids.end(), mine.begin(), mine.end());
    });
  }
  for (std::thread& thread : threads) thread.join();
  ASSERT_EQ(ids.size(), static_cast<size_t>(kThreads * kPerThread));
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), ids.size());
  EXPECT_EQ(registry->List(kStart).size(), ids.size());
}

TEST(WorkerRegistryNamesTest, RoleAndStateNames) {
  EXPECT_EQ(WorkerRoleName(WorkerRole::kLearner), "learner");
  EXPECT_EQ(WorkerRoleName(WorkerRole::kActor), "actor");
  EXPECT_EQ(WorkerStateName(WorkerState::kAlive), "alive");
  EXPECT_EQ(WorkerStateName(WorkerState::kLost), "lost");
}

}  // namespace
}  // namespace dcs::coordinator
