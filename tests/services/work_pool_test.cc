// Copyright 2026 The DCS Authors.
//
// WorkPool (services/work_pool.h): tasks run on the pool's own threads, a full queue refuses
// at once instead of blocking its caller, and the destructor runs what was queued.

#include "services/work_pool.h"

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "absl/synchronization/blocking_counter.h"
#include "absl/synchronization/notification.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

TEST(WorkPoolTest, RunsEveryTaskOnItsOwnThreads) {
  WorkPool pool({.threads = 2, .max_queued = 100});
  constexpr int kTasks = 50;
  absl::BlockingCounter done(kTasks);
  std::atomic<int> on_caller = 0;
  const std::thread::id caller = std::this_thread::get_id();
  for (int i = 0; i < kTasks; ++i) {
    ASSERT_TRUE(pool.Schedule([&] {
                      if (std::this_thread::get_id() == caller) ++on_caller;
                      done.DecrementCount();
                    }).ok());
  }
  done.Wait();
  EXPECT_EQ(on_caller, 0);
}

TEST(WorkPoolTest, AFullQueueRefusesAtOnceWithoutRunningTheTask) {
  WorkPool pool({.threads = 1, .max_queued = 2});
  absl::Notification release;
  absl::Notification running;
  ASSERT_TRUE(pool.Schedule([&] {
                    running.Notify();
                    release.WaitForNotification();
                  }).ok());
  running.WaitForNotification();  // the one thread is busy: what follows waits in the queue
  absl::BlockingCounter queued_ran(2);
  ASSERT_TRUE(pool.Schedule([&] { queued_ran.DecrementCount(); }).ok());
  ASSERT_TRUE(pool.Schedule([&] { queued_ran.DecrementCount(); }).ok());
  bool refused_ran = false;
  const absl::Status full = pool.Schedule([&] { refused_ran = true; });
  EXPECT_TRUE(absl::IsResourceExhausted(full)) << full;
  EXPECT_THAT(full.message(), HasSubstr("2 calls wait"));

  // Drained, it takes work again; the refused task never ran.
  release.Notify();
  queued_ran.Wait();
  absl::Notification after;
  ASSERT_TRUE(pool.Schedule([&] { after.Notify(); }).ok());
  after.WaitForNotification();
  EXPECT_FALSE(refused_ran);
}

TEST(WorkPoolTest, TheDestructorRunsWhatWasQueued) {
  std::atomic<int> ran = 0;
  {
    WorkPool pool({.threads = 1, .max_queued = 10});
    absl::Notification release;
    ASSERT_TRUE(pool.Schedule([&] { release.WaitForNotification(); }).ok());
    for (int i = 0; i < 5; ++i) ASSERT_TRUE(pool.Schedule([&] { ++ran; }).ok());
    release.Notify();
  }
  EXPECT_EQ(ran, 5);
}

}  // namespace
}  // namespace dcs::services
