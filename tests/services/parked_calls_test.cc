// Copyright 2026 The DCS Authors.
//
// ParkedCalls (services/parked_calls.h): a parked call is attempted at once and whenever its
// topic is woken, and ends in exactly one successful attempt or one expiry; a wake that comes
// while its call is being attempted is not lost; calls of one question are tried until one finds
// nothing, and not again until their topic is woken.

#include "services/parked_calls.h"

#include <atomic>
#include <memory>
#include <string>
#include <vector>

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
               std::shared_ptr<Record> record, std::shared_ptr<std::atomic<bool>> found,
               const std::string& question = "") {
  parked.Park(
      topic, question, absl::Now() + wait,
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
      "jobs", /*question=*/"", absl::Now() + absl::Hours(1),
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

// Work that parked calls take one piece at a time, and how often they asked for it.
struct Pieces {
  std::atomic<int> left = 0;
  std::atomic<int> attempts = 0;
  std::atomic<int> taken = 0;
};

// Parks a call that takes a piece of `pieces` if one is left.
void ParkTaking(ParkedCalls& parked, const std::string& question, absl::Duration wait,
                std::shared_ptr<Pieces> pieces, std::shared_ptr<Record> record) {
  parked.Park(
      "slots", question, absl::Now() + wait,
      [pieces, record] {
        ++pieces->attempts;
        ++record->attempts;
        int left = pieces->left;
        while (left > 0 && !pieces->left.compare_exchange_weak(left, left - 1)) {
        }
        if (left <= 0) return false;
        ++pieces->taken;
        record->finished = true;
        return true;
      },
      [record] { ++record->expiries; });
}

TEST(ParkedCallsTest, AWakeTriesTheCallsOfAQuestionUntilOneFindsNothing) {
  ParkedCalls parked;
  auto pieces = std::make_shared<Pieces>();
  std::vector<std::shared_ptr<Record>> asking;
  for (int i = 0; i < 6; ++i) {
    asking.push_back(std::make_shared<Record>());
    ParkTaking(parked, "numerics A", absl::Hours(1), pieces, asking.back());
  }
  // Parking tries them; once one found nothing, the others of its question wait for a wake.
  ASSERT_TRUE(Eventually([&] { return pieces->attempts >= 1; }));
  absl::SleepFor(absl::Milliseconds(50));
  const int parking_attempts = pieces->attempts;

  pieces->left = 2;
  parked.Wake("slots");
  // Two calls take the pieces, a third finds nothing, the other three are not asked.
  ASSERT_TRUE(Eventually([&] { return pieces->attempts == parking_attempts + 3; }));
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_EQ(pieces->attempts, parking_attempts + 3);
  EXPECT_EQ(pieces->taken, 2);
  // The longest parked are served first.
  EXPECT_TRUE(asking[0]->finished);
  EXPECT_TRUE(asking[1]->finished);

  // A wake with nothing to take costs one attempt, however many calls are parked.
  parked.Wake("slots");
  ASSERT_TRUE(Eventually([&] { return pieces->attempts == parking_attempts + 4; }));
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_EQ(pieces->attempts, parking_attempts + 4);

  // The question is known to have no answer: a call that parks with it is not tried.
  asking.push_back(std::make_shared<Record>());
  ParkTaking(parked, "numerics A", absl::Hours(1), pieces, asking.back());
  absl::SleepFor(absl::Milliseconds(50));
  EXPECT_EQ(pieces->attempts, parking_attempts + 4);
  EXPECT_EQ(asking.back()->attempts, 0);
  // Until a wake: then the longest parked takes the piece.
  pieces->left = 1;
  parked.Wake("slots");
  ASSERT_TRUE(Eventually([&] { return asking[2]->finished.load(); }));
  EXPECT_FALSE(asking.back()->finished);
}

TEST(ParkedCallsTest, AWakeDuringARoundLeavesItsQuestionOpen) {
  ParkedCalls parked;
  auto pieces = std::make_shared<Pieces>();
  absl::Notification attempting;
  absl::Notification release;
  auto first = std::make_shared<Record>();
  parked.Park(
      "slots", "numerics A", absl::Now() + absl::Hours(1),
      [&, first] {
        const int left = pieces->left;
        if (++first->attempts == 1) {
          // Two pieces come, and their wake, after this attempt looked and before it returns.
          attempting.Notify();
          release.WaitForNotification();
        }
        if (left == 0) return false;
        --pieces->left;
        first->finished = true;
        return true;
      },
      [] {});
  attempting.WaitForNotification();
  pieces->left = 2;
  parked.Wake("slots");
  release.Notify();
  ASSERT_TRUE(Eventually([&] { return first->finished.load(); }));
  // The first attempt's "nothing" was overtaken by the wake: a call parking now is tried.
  auto second = std::make_shared<Record>();
  ParkTaking(parked, "numerics A", absl::Hours(1), pieces, second);
  EXPECT_TRUE(Eventually([&] { return second->finished.load(); }));
}

TEST(ParkedCallsTest, OtherQuestionsAndCallsOfTheirOwnAreStillTried) {
  ParkedCalls parked;
  auto pieces = std::make_shared<Pieces>();
  auto first = std::make_shared<Record>();
  auto other_numerics = std::make_shared<Record>();
  auto own = std::make_shared<Record>();
  ParkTaking(parked, "numerics A", absl::Hours(1), pieces, first);
  ParkTaking(parked, "numerics B", absl::Hours(1), pieces, other_numerics);
  ParkTaking(parked, "", absl::Hours(1), pieces, own);
  ASSERT_TRUE(Eventually([&] { return pieces->attempts == 3; }));
  pieces->left = 5;
  parked.Wake("slots");
  EXPECT_TRUE(Eventually(
      [&] { return first->finished && other_numerics->finished && own->finished; }));
}

TEST(ParkedCallsTest, ACallNotAskedInARoundStillExpiresAtItsDeadline) {
  ParkedCalls parked;
  auto pieces = std::make_shared<Pieces>();
  auto asked = std::make_shared<Record>();
  auto not_asked = std::make_shared<Record>();
  ParkTaking(parked, "numerics A", absl::Milliseconds(100), pieces, asked);
  ParkTaking(parked, "numerics A", absl::Milliseconds(100), pieces, not_asked);
  EXPECT_TRUE(Eventually([&] { return asked->expiries == 1 && not_asked->expiries == 1; }));
  EXPECT_FALSE(asked->finished || not_asked->finished);
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
