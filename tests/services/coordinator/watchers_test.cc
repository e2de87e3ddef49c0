// Copyright 2026 The DCS Authors.
//
// Watchers (services/coordinator/watchers.h): a watcher looks at its first Touch and after each
// change of a topic it follows, never after another topic's; a burst of changes costs one look,
// no sooner than the interval after the last; Remove waits for a running look; Close stops
// every watcher and each added later.

#include "services/coordinator/watchers.h"

#include <atomic>
#include <memory>
#include <thread>

#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "gtest/gtest.h"
#include "tests/testing/eventually.h"

namespace dcs::services {
namespace {

using ::dcs::testing::Eventually;

struct Record {
  std::atomic<int> looks = 0;
  std::atomic<int> stops = 0;
};

int64_t AddWatcher(Watchers& watchers, std::vector<std::string> topics,
                   std::shared_ptr<Record> record) {
  return watchers.Add(
      std::move(topics), absl::ZeroDuration(), [record] { ++record->looks; },
      [record] { ++record->stops; });
}

TEST(WatchersTest, AWatcherLooksAtItsTouchAndAtChangesOfItsTopicsOnly) {
  Watchers watchers;
  auto run = std::make_shared<Record>();
  auto sentinel = std::make_shared<Record>();
  const int64_t run_watcher = AddWatcher(watchers, {"run run-1"}, run);
  EXPECT_EQ(run->looks, 0);  // not before its first Touch
  watchers.Touch(run_watcher);
  ASSERT_TRUE(Eventually([&] { return run->looks == 1; }));
  const int64_t sentinel_watcher = AddWatcher(watchers, {"run run-2"}, sentinel);
  watchers.Touch(sentinel_watcher);
  ASSERT_TRUE(Eventually([&] { return sentinel->looks == 1; }));

  // Had the other run's change marked it, it would look before the sentinel, whose last look
  // is later.
  watchers.Notify("run run-3");
  watchers.Notify("run run-2");
  ASSERT_TRUE(Eventually([&] { return sentinel->looks == 2; }));
  EXPECT_EQ(run->looks, 1);

  watchers.Notify("run run-1");
  EXPECT_TRUE(Eventually([&] { return run->looks == 2; }));
  watchers.NotifyAll();
  EXPECT_TRUE(Eventually([&] { return run->looks == 3 && sentinel->looks == 3; }));
  watchers.Remove(run_watcher);
  watchers.Remove(sentinel_watcher);
}

TEST(WatchersTest, AWatcherFollowsItsNewTopicsInsteadOfItsOld) {
  Watchers watchers;
  auto sweep = std::make_shared<Record>();
  const int64_t id = AddWatcher(watchers, {"sweep sweep-1"}, sweep);
  watchers.Follow(id, {"sweep sweep-1", "run run-7"});
  watchers.Notify("run run-7");
  ASSERT_TRUE(Eventually([&] { return sweep->looks == 1; }));
  watchers.Follow(id, {"sweep sweep-1"});
  auto sentinel = std::make_shared<Record>();
  const int64_t sentinel_watcher = AddWatcher(watchers, {"run run-8"}, sentinel);
  watchers.Touch(sentinel_watcher);
  ASSERT_TRUE(Eventually([&] { return sentinel->looks == 1; }));
  watchers.Notify("run run-7");  // no longer followed
  watchers.Notify("run run-8");
  ASSERT_TRUE(Eventually([&] { return sentinel->looks == 2; }));
  EXPECT_EQ(sweep->looks, 1);
  watchers.Remove(id);
  watchers.Remove(sentinel_watcher);
}

TEST(WatchersTest, ABurstOfChangesDuringALookCostsOneMoreLook) {
  Watchers watchers;
  absl::Notification looking;
  absl::Notification release;
  std::atomic<int> looks = 0;
  const int64_t id = watchers.Add(
      {"run run-1"}, absl::ZeroDuration(),
      [&] {
        if (++looks == 1) {
          looking.Notify();
          release.WaitForNotification();
        }
      },
      [] {});
  watchers.Touch(id);
  looking.WaitForNotification();
  for (int i = 0; i < 100; ++i) watchers.Notify("run run-1");
  release.Notify();
  ASSERT_TRUE(Eventually([&] { return looks == 2; }));
  watchers.Remove(id);  // no look runs once it returns
  EXPECT_EQ(looks, 2);
}

TEST(WatchersTest, AWatcherLooksAgainNoSoonerThanTheIntervalAfterItsLastLook) {
  constexpr absl::Duration kInterval = absl::Milliseconds(200);
  Watchers watchers;
  std::vector<absl::Time> looks;
  absl::Mutex mu;
  const int64_t id = watchers.Add(
      {"run run-1"}, kInterval,
      [&] {
        absl::MutexLock lock(&mu);
        looks.push_back(absl::Now());
      },
      [] {});
  watchers.Touch(id);
  auto looked = [&](size_t count) {
    absl::MutexLock lock(&mu);
    return looks.size() == count;
  };
  ASSERT_TRUE(Eventually([&] { return looked(1); }));
  watchers.Notify("run run-1");
  watchers.Notify("run run-1");
  ASSERT_TRUE(Eventually([&] { return looked(2); }));
  watchers.Remove(id);
  absl::MutexLock lock(&mu);
  ASSERT_EQ(looks.size(), 2);
  EXPECT_GE(looks[1] - looks[0], kInterval);
}

TEST(WatchersTest, RemoveWaitsForTheWatchersRunningLook) {
  Watchers watchers;
  absl::Notification looking;
  std::atomic<bool> look_ended = false;
  const int64_t id = watchers.Add(
      {"run run-1"}, absl::ZeroDuration(),
      [&] {
        looking.Notify();
        absl::SleepFor(absl::Milliseconds(100));
        look_ended = true;
      },
      [] {});
  watchers.Touch(id);
  looking.WaitForNotification();
  watchers.Remove(id);
  EXPECT_TRUE(look_ended);
  EXPECT_EQ(watchers.size(), 0);
}

TEST(WatchersTest, CloseStopsEveryWatcherAndEachAddedLater) {
  Watchers watchers;
  auto first = std::make_shared<Record>();
  auto later = std::make_shared<Record>();
  const int64_t id = AddWatcher(watchers, {"run run-1"}, first);
  EXPECT_EQ(watchers.size(), 1);
  watchers.Close();
  EXPECT_EQ(first->stops, 1);
  EXPECT_EQ(AddWatcher(watchers, {"run run-2"}, later), 0);
  EXPECT_EQ(later->stops, 1);
  EXPECT_EQ(watchers.size(), 1);  // until its owner removes it
  watchers.Remove(id);
  EXPECT_EQ(watchers.size(), 0);
}

}  // namespace
}  // namespace dcs::services
