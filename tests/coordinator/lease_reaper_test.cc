// Copyright 2026 The DCS Authors.
//
// LeaseReaper: lapsed leases back to the queue at each tick, by the test's clock; live ones
// left; every lapse counted once, those an Acquire found first included.

#include "coordinator/lease_reaper.h"

#include <memory>
#include <optional>

#include "absl/time/time.h"
#include "coordinator/store.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);
const absl::Duration kLease = absl::Seconds(10);

class LeaseReaperTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    absl::StatusOr<std::unique_ptr<Store>> store =
        Store::Open(Path("coordinator.db"), {.lease_duration = kLease}, kStart);
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = *std::move(store);
  }

  // A run submitted and leased to `learner` at `now`.
  LearnerLease SubmitAndLease(const std::string& request_id, const std::string& learner,
                              absl::Time now) {
    EXPECT_TRUE(store_->runs()
                    .SubmitRun({.request_id = request_id,
                                .config = "env: cartpole\n",
                                .env = "cartpole",
                                .n_envs = 1,
                                .total_timesteps = 1000},
                               now)
                    .ok());
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store_->runs().AcquireRun(learner, "127.0.0.1:1", "N", now);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? **lease : LearnerLease{};
  }

  RunState StateOf(const LearnerLease& lease) {
    absl::StatusOr<RunRecord> run = store_->runs().GetRun(lease.key.run_id);
    EXPECT_TRUE(run.ok()) << run.status();
    return run.ok() ? run->state : RunState::kFailed;
  }

  std::unique_ptr<Store> store_;
};

TEST_F(LeaseReaperTest, ReturnsALapsedLeaseToTheQueueAndLeavesALiveOne) {
  LeaseReaper reaper(*store_);
  const LearnerLease silent = SubmitAndLease("a", "L1", kStart);
  const LearnerLease renewing = SubmitAndLease("b", "L2", kStart);
  LeaseReaper::Reaped reaped = reaper.Tick(kStart + kLease / 2);
  EXPECT_TRUE(reaped.status.ok()) << reaped.status;
  EXPECT_EQ(reaped.lapsed, 0);

  const absl::Time later = kStart + kLease + absl::Seconds(1);
  ASSERT_TRUE(store_->runs().RenewLease(renewing.key, kStart + kLease / 2).ok());
  reaped = reaper.Tick(later);
  EXPECT_TRUE(reaped.status.ok()) << reaped.status;
  EXPECT_EQ(reaped.lapsed, 1);
  EXPECT_EQ(StateOf(silent), RunState::kQueued);
  EXPECT_EQ(StateOf(renewing), RunState::kRunning);
  EXPECT_EQ(reaper.Tick(later).lapsed, 0);  // counted once
}

// Under load the workers' Acquire calls expire nearly every lapsed lease before the reaper
// does; the reaper counts those too, once, and none from before it was made.
TEST_F(LeaseReaperTest, CountsTheLapsesAnAcquireFoundFirst) {
  SubmitAndLease("a", "L1", kStart);
  const absl::Time lapsed = kStart + kLease + absl::Seconds(1);
  SubmitAndLease("b", "L2", lapsed);  // its Acquire expires a's lease and takes a
  LeaseReaper reaper(*store_);  // made after that lapse: it is not this reaper's to count
  EXPECT_EQ(reaper.Tick(lapsed).lapsed, 0);

  const absl::Time later = lapsed + kLease + absl::Seconds(1);
  SubmitAndLease("c", "L3", later);  // its Acquire expires L2's lease
  const LeaseReaper::Reaped reaped = reaper.Tick(later);
  EXPECT_TRUE(reaped.status.ok()) << reaped.status;
  EXPECT_EQ(reaped.lapsed, 1);
}

}  // namespace
}  // namespace dcs::coordinator
