// Copyright 2026 The DCS Authors.
//
// ParkedCalls (services/parked_calls.h): a parked call is attempted at once and whenever its
// topic is woken, and ends in exactly one successful attempt or one expiry; a wake that comes
// while its call is being attempted is not lost.

#include "services/parked_calls.h"

#include <atomic>
#include <memory>

#include "absl/synchronization/notification.h"
#include "absl/time/clock.h"
#include "gtest/gtest.h"
#include "tests/testing/eventually.h"

namespace dcs::services {
namespace {

using ::dcs::testing::Eventually;

// A parked call's record: how often it was attempted, whether it finished or expired.
struct Record {
  std::atomic<int> attempts = 0;
  std::atomic<bool> finished = false;
  std::atomic<int> expiries = 0;
};

// Parks a call that finishes once `found` holds.
void ParkUntil(ParkedCalls& parked, const std::string& topic, absl::Duration wait,
               std::shared_ptr<Record> record, std::shared_ptr<std::atomic<bool>> found) {
  parked.Park(
      topic, absl::Now() + wait,
      [record, found] {
        ++record->attempts;
        if (!*found) return false;
        record->finished = true;
        return true;
      },
      [record] { ++record->expiries; });
}

TEST(ParkedCallsTest, ACallThatFindsWorkAtOnceFinishesWithoutWaiting) {
  ParkedCalls parked;
  auto record = std::make_shared<Record>();
  ParkUntil(parked, "jobs", absl::Hours(1), record, std::make_shared<std::atomic<bool>>(true));
  EXPECT_TRUE(Eventually([&] { return record->finished.load(); }));
  EXPECT_EQ(record->attempts, 1);
  EXPECT_EQ(record->expiries, 0);
}

TEST(ParkedCallsTest, AWakeOfItsTopicFinishesAParkedCall) {
  ParkedCalls parked;
  auto record = std::make_shared<Record>();
  auto other = std::make_shared<Record>();
  auto found = std::make_shared<std::atomic<bool>>(false);
  ParkUntil(parked, "jobs", absl::Hours(1), record, found);
  ParkUntil(parked, "runs", absl::Hours(1), other, found);
  ASSERT_TRUE(Eventually([&] { return record->attempts == 1 && other->attempts == 1; }));
  *found = true;
  parked.Wake("jobs");
  EXPECT_TRUE(Eventually([&] { return record->finished.load(); }));
  EXPECT_EQ(record->attempts, 2);
  EXPECT_EQ(record->expiries, 0);
  // The other topic's call was not tried again.
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_EQ(other->attempts, 1);
  EXPECT_FALSE(other->finished);
}

TEST(ParkedCallsTest, ACallThatFindsNothingExpiresAtItsDeadline) {
  ParkedCalls parked;
  auto record = std::make_shared<Record>();
  const absl::Time start = absl::Now();
  ParkUntil(parked, "jobs", absl::Milliseconds(100), record,
            std::make_shared<std::atomic<bool>>(false));
  ASSERT_TRUE(Eventually([&] { return record->expiries == 1; }));
  EXPECT_GE(absl::Now() - start, absl::Milliseconds(100));
  EXPECT_FALSE(record->finished);
  EXPECT_EQ(record->attempts, 1);
}

TEST(ParkedCallsTest, AWakeDuringAnAttemptIsNotLost) {
  ParkedCalls parked;
  auto found = std::make_shared<std::atomic<bool>>(false);
  absl::Notification attempting;
  absl::Notification release;
  std::atomic<int> attempts = 0;
  std::atomic<bool> finished = false;
  parked.Park(
      "jobs", absl::Now() + absl::Hours(1),
      [&] {
        const bool work = *found;
        if (++attempts == 1) {
          // The work comes, and its wake, after this attempt looked and before it returns.
          attempting.Notify();
          release.WaitForNotification();
        }
        if (!work) return false;
        finished = true;
        return true;
      },
      [] {});
  attempting.WaitForNotification();
  *found = true;
  parked.Wake("jobs");
  release.Notify();
  EXPECT_TRUE(Eventually([&] { return finished.load(); }));
  EXPECT_EQ(attempts, 2);
}

TEST(ParkedCallsTest, DestroyingExpiresEveryParkedCall) {
  auto record = std::make_shared<Record>();
  {
    ParkedCalls parked;
    ParkUntil(parked, "jobs", absl::Hours(1), record, std::make_shared<std::atomic<bool>>(false));
    ASSERT_TRUE(Eventually([&] { return record->attempts == 1; }));
  }
  EXPECT_EQ(record->expiries, 1);
  EXPECT_FALSE(record->finished);
}

}  // namespace
}  // namespace dcs::services
