// Copyright 2026 The DCS Authors.
#include "services/signals.h"

#include <pthread.h>
#include <signal.h>

#include "absl/time/time.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

bool IsBlocked(int signal) {
  sigset_t mask;
  pthread_sigmask(SIG_BLOCK, nullptr, &mask);
  return sigismember(&mask, signal) == 1;
}

TEST(BlockedSignalsTest, BlocksWhileAliveAndRestoresAfter) {
  ASSERT_FALSE(IsBlocked(SIGUSR1));
  {
    BlockedSignals blocked({SIGUSR1, SIGUSR2});
    EXPECT_TRUE(IsBlocked(SIGUSR1));
    EXPECT_TRUE(IsBlocked(SIGUSR2));
    EXPECT_FALSE(sigismember(&blocked.original_mask(), SIGUSR1));
  }
  EXPECT_FALSE(IsBlocked(SIGUSR1));
  EXPECT_FALSE(IsBlocked(SIGUSR2));
}

TEST(BlockedSignalsTest, WaitReturnsPendingSignalsOfTheSet) {
  BlockedSignals blocked({SIGUSR1, SIGUSR2});
  // raise() targets this thread, where the signals are blocked: they stay pending.
  ASSERT_EQ(::raise(SIGUSR2), 0);
  EXPECT_EQ(blocked.Wait(absl::Seconds(10)), SIGUSR2);
  ASSERT_EQ(::raise(SIGUSR1), 0);
  EXPECT_EQ(blocked.Wait(), SIGUSR1);
}

TEST(BlockedSignalsTest, WaitTimesOutWithZero) {
  BlockedSignals blocked({SIGUSR1});
  EXPECT_EQ(blocked.Wait(absl::Milliseconds(20)), 0);
}

}  // namespace
}  // namespace dcs::services
