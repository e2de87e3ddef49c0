// Copyright 2026 The DCS Authors.
//
// The coordinator's run collector over a real store: which series a scrape shows, with which
// labels, and what it leaves out (a queued run's checkpoint age, a score not known yet).

#include "services/coordinator/run_collector.h"

#include <cmath>
#include <map>
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

namespace dcs::services {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::Pair;
using ::testing::UnorderedElementsAre;
using Labels = std::map<std::string, std::string>;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);
absl::Time Now() { return kStart + absl::Seconds(30); }

// Family name -> its series, each as its labels to its value.
std::map<std::string, std::map<Labels, double>> Scrape(const RunCollector& collector) {
  std::map<std::string, std::map<Labels, double>> scraped;
  for (const prometheus::MetricFamily& family : collector.Collect()) {
    std::map<Labels, double>& series = scraped[family.name];
    for (const prometheus::ClientMetric& metric : family.metric) {
      Labels labels;
      for (const prometheus::ClientMetric::Label& label : metric.label) {
        labels[label.name] = label.value;
      }
      series[labels] = metric.gauge.value;
    }
  }
  return scraped;
}

class RunCollectorTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    absl::StatusOr<std::unique_ptr<coordinator::Store>> store = coordinator::Store::Open(
        Path("coordinator.db"), {.lease_duration = absl::Seconds(10)}, kStart);
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = *std::move(store);
    coordinator::SweepSubmission sweep{
        .request_id = "s", .name = "grid", .spec = "conditions: []\n", .seeds = 2};
    sweep.trials.push_back({.condition = "sine", .family = "sinusoidal", .observe = "live"});
    for (int seed = 0; seed < 2; ++seed) {
      sweep.runs.push_back({.trial = 0,
                            .run = {.request_id = absl::StrCat("s/", seed),
                                    .config = "env: cartpole\n",
                                    .env = "cartpole",
                                    .n_envs = 1,
                                    .total_timesteps = 1000}});
    }
    ASSERT_TRUE(store_->sweeps().SubmitSweep(sweep, kStart).ok());
  }

  coordinator::LeaseKey Acquire() {
    absl::StatusOr<std::optional<coordinator::LearnerLease>> lease =
        store_->runs().AcquireRun("L", "127.0.0.1:5000", "N", kStart);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? (*lease)->key : coordinator::LeaseKey{};
  }

  std::unique_ptr<coordinator::Store> store_;
};

TEST_F(RunCollectorTest, ShowsEachLiveRunsProgressAndScoresAndEachSweepsBestTrial) {
  const RunCollector collector(*store_, dir().string(), &Now);
  const coordinator::LeaseKey key = Acquire();  // run-1; run-2 stays queued
  ASSERT_TRUE(store_->runs().ReportProgress(key, {.timesteps = 512}, kStart).ok());
  ASSERT_TRUE(store_->checkpoints()
                  .RecordCheckpoint(key, {"000000000512", 512, "a"},
                                    coordinator::EvaluationScores{.latest_step = 512,
                                                                  .latest_avg_combined = 40,
                                                                  .latest_id_return = 50,
                                                                  .latest_ood_low_return =
                                                                      std::nan(""),
                                                                  .latest_ood_high_return = 30,
                                                                  .best_step = 256,
                                                                  .best_avg_combined = 45},
                                    kStart + absl::Seconds(10))
                  .ok());
  auto scraped = Scrape(collector);
  const Labels run1 = {
      {"run_id", "run-1"}, {"sweep_id", "sweep-1"}, {"condition", "sine"}, {"observe", "live"}};
  const Labels run2 = {
      {"run_id", "run-2"}, {"sweep_id", "sweep-1"}, {"condition", "sine"}, {"observe", "live"}};
  const auto with = [](Labels labels, const std::string& name, const std::string& value) {
    labels[name] = value;
    return labels;
  };
  EXPECT_THAT(scraped["dcs_run_step"], UnorderedElementsAre(Pair(run1, 512), Pair(run2, 0)));
  EXPECT_THAT(scraped["dcs_run_total_timesteps"],
              UnorderedElementsAre(Pair(run1, 1000), Pair(run2, 1000)));
  EXPECT_THAT(scraped["dcs_run_evaluation_avg_combined"],
              UnorderedElementsAre(Pair(with(run1, "which", "latest"), 40),
                                   Pair(with(run1, "which", "best"), 45)));
  EXPECT_THAT(scraped["dcs_run_evaluation_step"],
              UnorderedElementsAre(Pair(with(run1, "which", "latest"), 512),
                                   Pair(with(run1, "which", "best"), 256)));
  // No series for a split without contexts.
  EXPECT_THAT(scraped["dcs_run_evaluation_return"],
              UnorderedElementsAre(Pair(with(run1, "split", "id"), 50),
                                   Pair(with(run1, "split", "ood_high"), 30)));
  // The queued run has no checkpoint age: nothing is expected to checkpoint it.
  EXPECT_THAT(scraped["dcs_run_checkpoint_age_seconds"], ElementsAre(Pair(run1, 20)));
  EXPECT_THAT(scraped["dcs_sweep_best_avg_combined"], IsEmpty());
  EXPECT_THAT(scraped["dcs_evaluation_oldest_pending_seconds"], ElementsAre(Pair(Labels{}, 0)));
  EXPECT_GT(scraped["dcs_store_bytes"][Labels{}], 0);
  EXPECT_GT(scraped["dcs_data_dir_capacity_bytes"][Labels{}], 0);
  EXPECT_THAT(scraped["dcs_data_dir_free_bytes"], ElementsAre(Pair(Labels{}, ::testing::Ge(0))));

  // Both runs complete: their series go, the sweep's tally and best trial stay.
  ASSERT_TRUE(store_->runs().ReportProgress(key, {.avg_combined = 40}, kStart).ok());
  ASSERT_TRUE(store_->runs().FinishRun(key, coordinator::RunState::kCompleted, "", kStart).ok());
  const coordinator::LeaseKey second = Acquire();
  ASSERT_TRUE(store_->runs().ReportProgress(second, {.avg_combined = 60}, kStart).ok());
  ASSERT_TRUE(
      store_->runs().FinishRun(second, coordinator::RunState::kCompleted, "", kStart).ok());
  scraped = Scrape(collector);
  EXPECT_THAT(scraped["dcs_run_step"], IsEmpty());
  EXPECT_THAT(scraped["dcs_sweep_best_avg_combined"],
              ElementsAre(Pair(Labels{{"sweep_id", "sweep-1"},
                                      {"condition", "sine"},
                                      {"observe", "live"}},
                               50)));
  EXPECT_EQ((scraped["dcs_sweep_runs"][Labels{{"sweep_id", "sweep-1"}, {"state", "completed"}}]),
            2);
}

TEST_F(RunCollectorTest, AnUnreadableDataDirectoryLeavesOnlyItsOwnSeriesOut) {
  const RunCollector collector(*store_, Path("missing"), &Now);
  const auto scraped = Scrape(collector);
  EXPECT_FALSE(scraped.contains("dcs_data_dir_free_bytes"));
  EXPECT_FALSE(scraped.contains("dcs_data_dir_capacity_bytes"));
  EXPECT_TRUE(scraped.contains("dcs_runs"));
  EXPECT_TRUE(scraped.contains("dcs_store_bytes"));
}

}  // namespace
}  // namespace dcs::services
