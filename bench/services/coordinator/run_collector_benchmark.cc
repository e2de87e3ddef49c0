// Copyright 2026 The DCS Authors.
//
// One scrape of the coordinator's run metrics (RunCollector::Collect: Store::Counts and the
// families built from it), which holds the store's lock for its transaction, on a store like a
// busy fleet's: 200 runs running (in sweeps of 20, each run with a checkpoint and scores), 20
// queued, and a history of ended sweeps of 20 completed runs each:
//   BM_Collect/ended:0      no history
//   BM_Collect/ended:5000   5,000 completed runs in 250 ended sweeps
// The number that matters: wall time per scrape (Prometheus scrapes every 5 s by default).
// The store lives in a temporary directory (/dev/shm if there is one: building it commits
// thousands of synced transactions).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "benchmark/benchmark.h"
#include "coordinator/store.h"
#include "services/coordinator/run_collector.h"

namespace dcs::services {
namespace {

namespace fs = std::filesystem;
const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);

coordinator::SweepSubmission Sweep(const std::string& request_id, int runs) {
  coordinator::SweepSubmission sweep{
      .request_id = request_id, .name = "grid", .spec = "conditions: []\n", .seeds = runs / 4};
  for (int trial = 0; trial < 4; ++trial) {
    sweep.trials.push_back(
        {.condition = absl::StrCat("c", trial), .family = "static", .observe = "none"});
  }
  for (int i = 0; i < runs; ++i) {
    sweep.runs.push_back({.trial = i % 4,
                          .run = {.request_id = absl::StrCat(request_id, "/", i),
                                  .config = "env: cartpole\n",
                                  .env = "cartpole",
                                  .n_envs = 4,
                                  .total_timesteps = 150000}});
  }
  return sweep;
}

// Leases the next queued run; nullopt if none is.
std::optional<coordinator::LeaseKey> Acquire(coordinator::Store& store) {
  absl::StatusOr<std::optional<coordinator::LearnerLease>> lease =
      store.runs().AcquireRun("L", "127.0.0.1:1", "N", kStart);
  if (!lease.ok() || !lease->has_value()) return std::nullopt;
  return (*lease)->key;
}

// A store at `dir` with `ended` completed runs in ended sweeps, then 200 running and 20 queued.
std::unique_ptr<coordinator::Store> MakeStore(const std::string& dir, int ended) {
  absl::StatusOr<std::unique_ptr<coordinator::Store>> store =
      coordinator::Store::Open(dir + "/coordinator.db", {.lease_duration = absl::Hours(1)}, kStart);
  if (!store.ok()) return nullptr;
  int sweeps = 0;
  for (int i = 0; i < ended; i += 20) {
    if (!(*store)->sweeps().SubmitSweep(Sweep(absl::StrCat("e", ++sweeps), 20), kStart).ok()) {
      return nullptr;
    }
    while (const std::optional<coordinator::LeaseKey> key = Acquire(**store)) {
      (*store)->runs().ReportProgress(*key, {.timesteps = 150000, .avg_combined = i}, kStart)
          .IgnoreError();
      (*store)->runs().FinishRun(*key, coordinator::RunState::kCompleted, "", kStart)
          .IgnoreError();
    }
  }
  for (int i = 0; i < 11; ++i) {  // 220 runs: 200 to run, 20 left queued
    if (!(*store)->sweeps().SubmitSweep(Sweep(absl::StrCat("r", i), 20), kStart).ok()) {
      return nullptr;
    }
  }
  for (int i = 0; i < 200; ++i) {
    const std::optional<coordinator::LeaseKey> key = Acquire(**store);
    if (!key.has_value()) return nullptr;
    (*store)->runs().ReportProgress(*key, {.timesteps = 1000 * i}, kStart).IgnoreError();
    (*store)
        ->checkpoints()
        .RecordCheckpoint(*key, {"000000001000", 1000, "sha"},
                          coordinator::EvaluationScores{.latest_step = 1000,
                                                        .latest_avg_combined = 50,
                                                        .latest_id_return = 60,
                                                        .latest_ood_low_return = 40,
                                                        .latest_ood_high_return = 30,
                                                        .best_step = 1000,
                                                        .best_avg_combined = 50},
                          kStart)
        .IgnoreError();
  }
  return *std::move(store);
}

void BM_Collect(benchmark::State& state) {
  const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
  const std::string dir =
      (base / absl::StrCat("dcs-collect-", ::getpid(), "-", state.range(0))).string();
  fs::create_directories(dir);
  const std::unique_ptr<coordinator::Store> store = MakeStore(dir, state.range(0));
  if (store == nullptr) {
    state.SkipWithError("cannot build the store");
    return;
  }
  const RunCollector collector(*store, dir);
  size_t series = 0;
  for (auto _ : state) {
    const std::vector<prometheus::MetricFamily> families = collector.Collect();
    series = 0;
    for (const prometheus::MetricFamily& family : families) series += family.metric.size();
    benchmark::DoNotOptimize(series);
  }
  state.counters["series"] = static_cast<double>(series);
  fs::remove_all(dir);
}
BENCHMARK(BM_Collect)->ArgName("ended")->Arg(0)->Arg(5000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dcs::services
