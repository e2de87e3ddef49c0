// Copyright 2026 The DCS Authors.
#include "services/backoff.h"

#include <random>

#include "absl/random/random.h"
#include "absl/time/time.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

absl::BitGen SeededGen() {
  std::seed_seq seed = {20, 26, 11, 21};
  return absl::BitGen(seed);
}

BackoffPolicy NoJitter() {
  return {.initial = absl::Milliseconds(100),
          .multiplier = 3.0,
          .max = absl::Seconds(5),
          .jitter = 0.0};
}

TEST(BackoffDelayTest, ZeroJitterGrowsByMultiplierUpToMax) {
  absl::BitGen gen = SeededGen();
  const BackoffPolicy policy = NoJitter();
  EXPECT_EQ(BackoffDelay(policy, 1, gen), absl::Milliseconds(100));
  EXPECT_EQ(BackoffDelay(policy, 2, gen), absl::Milliseconds(300));
  EXPECT_EQ(BackoffDelay(policy, 3, gen), absl::Milliseconds(900));
  EXPECT_EQ(BackoffDelay(policy, 4, gen), absl::Milliseconds(2700));
  // 8100ms is past the cap.
  EXPECT_EQ(BackoffDelay(policy, 5, gen), absl::Seconds(5));
  EXPECT_EQ(BackoffDelay(policy, 6, gen), absl::Seconds(5));
}

TEST(BackoffDelayTest, VeryLargeAttemptStaysAtMax) {
  absl::BitGen gen = SeededGen();
  const BackoffPolicy policy = NoJitter();
  for (int attempt : {64, 65, 1000, 1 << 30}) {
    EXPECT_EQ(BackoffDelay(policy, attempt, gen), absl::Seconds(5)) << attempt;
  }
}

TEST(BackoffDelayTest, DefaultPolicyDoublesFrom250ms) {
  BackoffPolicy policy;
  policy.jitter = 0;
  absl::BitGen gen = SeededGen();
  EXPECT_EQ(BackoffDelay(policy, 1, gen), absl::Milliseconds(250));
  EXPECT_EQ(BackoffDelay(policy, 2, gen), absl::Milliseconds(500));
  EXPECT_EQ(BackoffDelay(policy, 6, gen), absl::Seconds(8));
  EXPECT_EQ(BackoffDelay(policy, 7, gen), absl::Seconds(8));
}

TEST(BackoffDelayTest, JitterStaysWithinBoundsAndActuallyVaries) {
  const BackoffPolicy policy = {
      .initial = absl::Seconds(1), .multiplier = 2.0, .max = absl::Seconds(4), .jitter = 0.25};
  absl::BitGen gen = SeededGen();
  for (int attempt : {1, 2, 3, 10}) {
    const absl::Duration base = std::min(absl::Seconds(4), absl::Seconds(1 << (attempt - 1)));
    absl::Duration lowest = absl::InfiniteDuration();
    absl::Duration highest = -absl::InfiniteDuration();
    for (int draw = 0; draw < 2000; ++draw) {
      const absl::Duration delay = BackoffDelay(policy, attempt, gen);
      ASSERT_GE(delay, base * 0.75) << "attempt " << attempt;
      ASSERT_LE(delay, base * 1.25) << "attempt " << attempt;
      lowest = std::min(lowest, delay);
      highest = std::max(highest, delay);
    }
    // The draws spread over most of the allowed range, on both sides of the base.
    EXPECT_LT(lowest, base * 0.8) << "attempt " << attempt;
    EXPECT_GT(highest, base * 1.2) << "attempt " << attempt;
  }
}

TEST(BackoffDelayTest, SameSeedGivesSameDelays) {
  const BackoffPolicy policy;
  absl::BitGen first = SeededGen();
  absl::BitGen second = SeededGen();
  for (int attempt = 1; attempt <= 10; ++attempt) {
    EXPECT_EQ(BackoffDelay(policy, attempt, first), BackoffDelay(policy, attempt, second));
  }
}

}  // namespace
}  // namespace dcs::services
