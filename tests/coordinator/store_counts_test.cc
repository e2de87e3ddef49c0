// Copyright 2026 The DCS Authors.
//
// What the coordinator's metrics read of its store (Store::Counts, coordinator/store_counts.h)
// on a real SQLite file: runs' furthest steps and scores, checkpoint times, the sweeps shown and
// their best trials, the oldest evaluation waiting.

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::Field;
using ::testing::Optional;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);
constexpr absl::Duration kLease = absl::Seconds(10);

RunSubmission Submission(const std::string& request_id) {
  return {.request_id = request_id,
          .config = "env: cartpole\n",
          .env = "cartpole",
          .n_envs = 1,
          .total_timesteps = 1000};
}

// A sweep of `trials` trials × `seeds` seeds, queued seed-major.
SweepSubmission Sweep(const std::string& request_id, int trials, int seeds) {
  SweepSubmission sweep{.request_id = request_id, .name = "grid", .spec = "conditions: []\n",
                        .seeds = seeds};
  for (int trial = 0; trial < trials; ++trial) {
    sweep.trials.push_back(
        {.condition = absl::StrCat("condition-", trial), .family = "static", .observe = "live"});
  }
  for (int seed = 0; seed < seeds; ++seed) {
    for (int trial = 0; trial < trials; ++trial) {
      sweep.runs.push_back(
          {.trial = trial, .run = Submission(absl::StrCat(request_id, "/", trial, "/", seed))});
    }
  }
  return sweep;
}

EvaluationScores Scores(int64_t latest_step, double latest, int64_t best_step, double best) {
  return {.latest_step = latest_step,
          .latest_avg_combined = latest,
          .latest_id_return = latest + 1,
          .latest_ood_low_return = std::nan(""),
          .latest_ood_high_return = latest - 1,
          .best_step = best_step,
          .best_avg_combined = best};
}

class StoreCountsTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    absl::StatusOr<std::unique_ptr<Store>> store =
        Store::Open(Path("coordinator.db"), {.lease_duration = kLease}, kStart);
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = *std::move(store);
  }

  // Leases the next queued run to a learner at `now`.
  LeaseKey Acquire(absl::Time now = kStart) {
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store_->runs().AcquireRun("L", "127.0.0.1:5000", "N", now);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? (*lease)->key : LeaseKey{};
  }

  StoreCounts Counts() {
    absl::StatusOr<StoreCounts> counts = store_->Counts();
    EXPECT_TRUE(counts.ok()) << counts.status();
    return counts.value_or(StoreCounts{});
  }

  std::unique_ptr<Store> store_;
};

TEST_F(StoreCountsTest, ARunsStepIsTheFurthestItsLearnersReachedAcrossAHandover) {
  ASSERT_TRUE(store_->runs().SubmitRun(Submission("r"), kStart).ok());
  const LeaseKey first = Acquire();
  ASSERT_TRUE(store_->runs().ReportProgress(first, {.timesteps = 512}, kStart).ok());
  // The learner dies; the next resumes from a checkpoint at step 256 and reports 384.
  ASSERT_TRUE(store_->ExpireLeases(kStart + 2 * kLease).ok());
  const LeaseKey second = Acquire(kStart + 2 * kLease);
  ASSERT_TRUE(store_->runs().ReportProgress(second, {.timesteps = 384}, kStart).ok());
  StoreCounts counts = Counts();
  ASSERT_EQ(counts.live_runs.size(), 1u);
  EXPECT_EQ(counts.live_runs[0].run_id, "run-1");
  EXPECT_EQ(counts.live_runs[0].timesteps, 512);
  EXPECT_EQ(counts.live_runs[0].total_timesteps, 1000);
  EXPECT_EQ(store_->runs().GetRun("run-1")->progress.timesteps, 512);
  ASSERT_TRUE(store_->runs().ReportProgress(second, {.timesteps = 640}, kStart).ok());
  EXPECT_EQ(Counts().live_runs[0].timesteps, 640);
}

TEST_F(StoreCountsTest, ARunsScoresComeWithItsCheckpointsAndNeverGoBack) {
  ASSERT_TRUE(store_->runs().SubmitRun(Submission("r"), kStart).ok());
  const LeaseKey key = Acquire();
  EXPECT_EQ(Counts().live_runs[0].scores, std::nullopt);
  ASSERT_TRUE(store_->checkpoints()
                  .RecordCheckpoint(key, {"000000000256", 256, "a"}, Scores(256, 10, 256, 10),
                                    kStart)
                  .ok());
  ASSERT_TRUE(store_->checkpoints()
                  .RecordCheckpoint(key, {"000000000512", 512, "b"}, Scores(512, 5, 512, 5),
                                    kStart)
                  .ok());
  // A resumed learner sends the evaluation at 256 again: neither the latest nor the best moves.
  ASSERT_TRUE(store_->checkpoints()
                  .RecordCheckpoint(key, {"000000000256", 256, "a"}, Scores(256, 10, 256, 10),
                                    kStart)
                  .ok());
  const std::optional<EvaluationScores> scores = Counts().live_runs[0].scores;
  ASSERT_TRUE(scores.has_value());
  EXPECT_EQ(scores->latest_step, 512);
  EXPECT_EQ(scores->latest_avg_combined, 5);
  EXPECT_EQ(scores->latest_id_return, 6);
  EXPECT_TRUE(std::isnan(scores->latest_ood_low_return));  // a split without contexts
  EXPECT_EQ(scores->latest_ood_high_return, 4);
  EXPECT_EQ(scores->best_step, 256);
  EXPECT_EQ(scores->best_avg_combined, 10);
}

TEST_F(StoreCountsTest, CheckpointAgeRunsFromTheLatestCheckpointOrElseTheLease) {
  ASSERT_TRUE(store_->runs().SubmitRun(Submission("r"), kStart).ok());
  EXPECT_EQ(Counts().live_runs[0].checkpointed_at, std::nullopt);  // queued
  const LeaseKey key = Acquire(kStart + absl::Seconds(3));
  EXPECT_THAT(Counts().live_runs[0].checkpointed_at, Optional(kStart + absl::Seconds(3)));
  ASSERT_TRUE(store_->checkpoints()
                  .RecordCheckpoint(key, {"000000000256", 256, "a"}, std::nullopt,
                                    kStart + absl::Seconds(7))
                  .ok());
  EXPECT_THAT(Counts().live_runs[0].checkpointed_at, Optional(kStart + absl::Seconds(7)));
  ASSERT_TRUE(store_->runs().FinishRun(key, RunState::kCompleted, "", kStart).ok());
  EXPECT_THAT(Counts().live_runs, ::testing::IsEmpty());  // ended: no series
}

TEST_F(StoreCountsTest, SweepsShownAreThoseWithWorkAheadAndTheTwentyMostRecent) {
  for (int i = 1; i <= kRecentSweeps + 2; ++i) {
    ASSERT_TRUE(store_->sweeps().SubmitSweep(Sweep(absl::StrCat("s", i), 1, 1), kStart).ok());
  }
  // sweep-1 still has work ahead; sweep-2 ended and is not among the 20 most recent.
  ASSERT_TRUE(store_->sweeps().CancelSweep("sweep-2", kStart).ok());
  std::vector<std::string> shown;
  for (const SweepCounts& sweep : Counts().sweeps) shown.push_back(sweep.sweep_id);
  std::vector<std::string> expected = {"sweep-1"};
  for (int i = 3; i <= kRecentSweeps + 2; ++i) expected.push_back(absl::StrCat("sweep-", i));
  EXPECT_EQ(shown, expected);
}

TEST_F(StoreCountsTest, ASweepsBestTrialIsDcsWatchsAndOutlivesTheSweep) {
  ASSERT_TRUE(store_->sweeps().SubmitSweep(Sweep("s", 2, 2), kStart).ok());  // runs 1 to 4
  EXPECT_EQ(Counts().sweeps[0].best, std::nullopt);
  // Trial 0 completes at 10 and 20 (IQM 15), trial 1 at 30 and 12 (IQM 21).
  for (double score : {10.0, 30.0, 20.0, 12.0}) {
    const LeaseKey key = Acquire();
    ASSERT_TRUE(store_->runs()
                    .ReportProgress(key, {.timesteps = 1000, .avg_combined = score}, kStart)
                    .ok());
    ASSERT_TRUE(store_->runs().FinishRun(key, RunState::kCompleted, "", kStart).ok());
  }
  const std::vector<SweepCounts> sweeps = Counts().sweeps;
  ASSERT_EQ(sweeps.size(), 1u);
  EXPECT_THAT(sweeps[0].best, Optional(AllOf(Field(&TrialScore::condition, "condition-1"),
                                              Field(&TrialScore::observe, "live"),
                                              Field(&TrialScore::score, 21))));
  EXPECT_EQ(sweeps[0].runs_by_state[static_cast<int>(RunState::kCompleted)].second, 4);
}

TEST_F(StoreCountsTest, TheOldestWaitingEvaluationIsWhenItWasSubmitted) {
  ASSERT_TRUE(store_->runs().SubmitRun(Submission("r"), kStart).ok());
  const LeaseKey key = Acquire();
  EXPECT_EQ(Counts().oldest_free_evaluation, std::nullopt);
  for (int version = 1; version <= 2; ++version) {
    ASSERT_TRUE(store_->evaluations()
                    .SubmitEvaluation(key,
                                      {.policy_version = version,
                                       .step = 256 * version,
                                       .contexts = 2,
                                       .episodes = 1,
                                       .weights = "w"},
                                      kStart + absl::Seconds(version))
                    .ok());
  }
  const StoreCounts counts = Counts();
  EXPECT_EQ(counts.free_evaluation_jobs, 4);
  EXPECT_THAT(counts.oldest_free_evaluation, Optional(kStart + absl::Seconds(1)));
  EXPECT_GT(counts.store_bytes, 0);
}

}  // namespace
}  // namespace dcs::coordinator
