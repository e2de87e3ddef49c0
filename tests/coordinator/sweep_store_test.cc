// Copyright 2026 The DCS Authors.
//
// The store's sweeps (coordinator/sweep_table.h) on a real SQLite file, and backups of a store
// holding them (Store::Backup).

#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "coordinator/run_state.h"
#include "coordinator/store.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);

// A sweep of `trials` trials × `seeds` seeds, queued seed-major.
SweepSubmission Sweep(std::string request_id, int trials, int seeds) {
  SweepSubmission sweep{.request_id = request_id, .name = "grid", .spec = "conditions: []\n",
                        .seeds = seeds};
  for (int trial = 0; trial < trials; ++trial) {
    sweep.trials.push_back({.condition = absl::StrCat("condition-", trial),
                            .family = trial == 0 ? "static" : "sinusoidal",
                            .observe = "none"});
  }
  for (int seed = 0; seed < seeds; ++seed) {
    for (int trial = 0; trial < trials; ++trial) {
      sweep.runs.push_back({.trial = trial,
                            .run = {.request_id = absl::StrCat(request_id, "/", trial, "/", seed),
                                    .config = "env: cartpole\n",
                                    .seed = static_cast<uint64_t>(seed),
                                    .env = "cartpole",
                                    .n_envs = 1,
                                    .total_timesteps = 1000}});
    }
  }
  return sweep;
}

int64_t CountIn(const SweepRecord& sweep, RunState wanted) {
  for (const auto& [state, runs] : sweep.runs_by_state) {
    if (state == wanted) return runs;
  }
  return -1;
}

class SweepStoreTest : public testing::TempDirTest {
 protected:
  std::unique_ptr<Store> Open() {
    absl::StatusOr<std::unique_ptr<Store>> store =
        Store::Open(Path("coordinator.db"), {.lease_duration = absl::Seconds(10)}, kStart);
    EXPECT_TRUE(store.ok()) << store.status();
    return store.ok() ? *std::move(store) : nullptr;
  }

  // Leases the next run to a learner and returns its id.
  static std::string Acquire(Store& store) {
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store.runs().AcquireRun("L", "127.0.0.1:5000", "N", kStart);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? (*lease)->run.id : "";
  }
};

TEST_F(SweepStoreTest, ASweepQueuesARunPerTrialAndSeedAndSurvivesReopening) {
  {
    std::unique_ptr<Store> store = Open();
    absl::StatusOr<SweepRecord> sweep = store->sweeps().SubmitSweep(Sweep("s", 3, 2), kStart);
    ASSERT_TRUE(sweep.ok()) << sweep.status();
    EXPECT_EQ(sweep->id, "sweep-1");
    EXPECT_EQ(sweep->state, SweepState::kQueued);
    EXPECT_EQ(CountIn(*sweep, RunState::kQueued), 6);
    ASSERT_EQ(sweep->trials.size(), 3u);
    EXPECT_EQ(sweep->trials[1].condition, "condition-1");
    // The same request again creates nothing.
    absl::StatusOr<SweepRecord> again = store->sweeps().SubmitSweep(Sweep("s", 3, 2), kStart);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->id, "sweep-1");
  }
  std::unique_ptr<Store> store = Open();
  absl::StatusOr<std::vector<RunRecord>> runs = store->sweeps().ListSweepRuns("sweep-1");
  ASSERT_TRUE(runs.ok()) << runs.status();
  ASSERT_EQ(runs->size(), 6u);
  EXPECT_EQ((*runs)[4].sweep_id, "sweep-1");
  EXPECT_EQ((*runs)[4].trial, 1);
  EXPECT_EQ((*runs)[4].submission.seed, 1u);
  absl::StatusOr<std::vector<SweepRecord>> sweeps = store->sweeps().ListSweeps();
  ASSERT_TRUE(sweeps.ok());
  EXPECT_EQ(sweeps->size(), 1u);
  // A run submitted alone belongs to no sweep.
  absl::StatusOr<RunRecord> alone = store->runs().SubmitRun(
      {.request_id = "alone", .config = "env: cartpole\n", .n_envs = 1}, kStart);
  ASSERT_TRUE(alone.ok());
  EXPECT_EQ(alone->sweep_id, "");
  EXPECT_EQ(alone->trial, std::nullopt);
}

TEST_F(SweepStoreTest, ABadRunLeavesNothingOfTheSweep) {
  std::unique_ptr<Store> store = Open();
  SweepSubmission sweep = Sweep("s", 2, 2);
  sweep.runs.back().trial = 2;
  EXPECT_THAT(store->sweeps().SubmitSweep(sweep, kStart).status().message(),
              HasSubstr("names trial 2"));
  sweep = Sweep("s", 2, 2);
  sweep.runs[1].run.request_id = sweep.runs[0].run.request_id;  // the runs table refuses it
  EXPECT_FALSE(store->sweeps().SubmitSweep(sweep, kStart).ok());
  absl::StatusOr<std::vector<SweepRecord>> sweeps = store->sweeps().ListSweeps();
  absl::StatusOr<std::vector<RunRecord>> runs = store->runs().ListRuns();
  ASSERT_TRUE(sweeps.ok() && runs.ok());
  EXPECT_TRUE(sweeps->empty());
  EXPECT_TRUE(runs->empty());
}

TEST_F(SweepStoreTest, ASmallSweepSubmittedAfterABigOneIsNotStarved) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("big", 10, 10), kStart).ok());
  EXPECT_EQ(Acquire(*store), "run-1");
  EXPECT_EQ(Acquire(*store), "run-2");
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("small", 1, 2), kStart).ok());  // runs 101 and 102
  // The small sweep has no running run: its run goes first, then the two sweeps take turns.
  EXPECT_EQ(Acquire(*store), "run-101");
  EXPECT_EQ(Acquire(*store), "run-102");
  EXPECT_EQ(Acquire(*store), "run-3");
}

TEST_F(SweepStoreTest, CancellingStopsEveryActiveRunAndRetryRequeuesOnlyFailedOnes) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("s", 2, 2), kStart).ok());
  // run-1 fails, run-2 completes; run-3 and run-4 stay queued.
  absl::StatusOr<std::optional<LearnerLease>> first =
      store->runs().AcquireRun("L", "a", "N", kStart);
  absl::StatusOr<std::optional<LearnerLease>> second =
      store->runs().AcquireRun("L", "a", "N", kStart);
  ASSERT_TRUE(first.ok() && first->has_value() && second.ok() && second->has_value());
  ASSERT_TRUE(store->runs().FinishRun((*first)->key, RunState::kFailed, "boom", kStart).ok());
  ASSERT_TRUE(store->runs().FinishRun((*second)->key, RunState::kCompleted, "", kStart).ok());
  absl::StatusOr<SweepRecord> sweep = store->sweeps().GetSweep("sweep-1");
  ASSERT_TRUE(sweep.ok());
  EXPECT_EQ(sweep->state, SweepState::kRunning);

  absl::StatusOr<SweepRecord> cancelled = store->sweeps().CancelSweep("sweep-1", kStart);
  ASSERT_TRUE(cancelled.ok()) << cancelled.status();
  EXPECT_EQ(cancelled->state, SweepState::kCancelled);
  EXPECT_EQ(CountIn(*cancelled, RunState::kCancelled), 2);
  EXPECT_EQ(store->sweeps().CancelSweep("sweep-1", kStart).status().code(),
            absl::StatusCode::kFailedPrecondition);

  absl::StatusOr<std::pair<SweepRecord, int>> retried =
      store->sweeps().RetrySweep("sweep-1", kStart);
  ASSERT_TRUE(retried.ok()) << retried.status();
  EXPECT_EQ(retried->second, 1);
  absl::StatusOr<RunRecord> run = store->runs().GetRun("run-1");
  ASSERT_TRUE(run.ok());
  EXPECT_EQ(run->state, RunState::kQueued);
  EXPECT_EQ(run->error, "");
  EXPECT_EQ(retried->first.state, SweepState::kRunning);
  EXPECT_THAT(store->sweeps().RetrySweep("sweep-1", kStart).status().message(),
              HasSubstr("no failed run"));
}

TEST_F(SweepStoreTest, ALearnerLeaseNamesTheRunsTrial) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("s", 2, 1), kStart).ok());
  ASSERT_TRUE(store->runs()
                  .SubmitRun({.request_id = "alone",
                              .config = "env: cartpole\n",
                              .env = "cartpole",
                              .total_timesteps = 1000},
                             kStart)
                  .ok());
  std::vector<std::pair<std::string, std::string>> trials;
  for (int i = 0; i < 3; ++i) {
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store->runs().AcquireRun("L", "a", "N", kStart);
    ASSERT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    trials.emplace_back((*lease)->condition, (*lease)->observe);
  }
  // Fair queueing leases the run alone second.
  EXPECT_THAT(trials, ElementsAre(std::pair("condition-0", "none"), std::pair("", ""),
                                  std::pair("condition-1", "none")));
}

TEST_F(SweepStoreTest, CountsEachSweepsRunsByStateAndStepsRemaining) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("done", 1, 1), kStart).ok());  // run-1
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("busy", 1, 3), kStart).ok());  // runs 2 to 4
  absl::StatusOr<std::optional<LearnerLease>> done =
      store->runs().AcquireRun("L", "a", "N", kStart);
  ASSERT_TRUE(done.ok() && done->has_value());
  ASSERT_EQ((*done)->key.run_id, "run-1");
  ASSERT_TRUE(store->runs().FinishRun((*done)->key, RunState::kCompleted, "", kStart).ok());
  absl::StatusOr<std::optional<LearnerLease>> running =
      store->runs().AcquireRun("L", "a", "N", kStart);
  ASSERT_TRUE(running.ok() && running->has_value());
  ASSERT_EQ((*running)->key.run_id, "run-2");
  ASSERT_TRUE(store->runs().ReportProgress((*running)->key, {.timesteps = 400}, kStart).ok());

  absl::StatusOr<StoreCounts> counts = store->Counts();
  ASSERT_TRUE(counts.ok()) << counts.status();
  ASSERT_EQ(counts->sweeps.size(), 2u);  // the ended one too: it is among the 20 most recent
  EXPECT_THAT(counts->sweeps[0].runs_by_state[static_cast<int>(RunState::kCompleted)],
              std::pair(RunState::kCompleted, 1));
  EXPECT_EQ(counts->sweeps[0].steps_remaining, 0);
  const SweepCounts& busy = counts->sweeps[1];
  EXPECT_EQ(busy.sweep_id, "sweep-2");
  EXPECT_THAT(busy.runs_by_state,
              ElementsAre(std::pair(RunState::kQueued, 2), std::pair(RunState::kRunning, 1),
                          std::pair(RunState::kCompleted, 0), std::pair(RunState::kFailed, 0),
                          std::pair(RunState::kCancelled, 0)));
  EXPECT_EQ(busy.steps_remaining, 2 * 1000 + 600);

  ASSERT_TRUE(store->sweeps().CancelSweep("sweep-2", kStart).ok());
  counts = store->Counts();
  ASSERT_TRUE(counts.ok()) << counts.status();
  ASSERT_EQ(counts->sweeps.size(), 2u);
  EXPECT_EQ(counts->sweeps[1].steps_remaining, 0);
}

TEST_F(SweepStoreTest, UnknownSweepsAreNotFound) {
  std::unique_ptr<Store> store = Open();
  EXPECT_EQ(store->sweeps().GetSweep("sweep-9").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(store->sweeps().GetSweep("run-1").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(store->sweeps().ListSweepRuns("sweep-9").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(store->sweeps().CancelSweep("sweep-9", kStart).status().code(),
            absl::StatusCode::kNotFound);
}

// What a test compares of a store's runs and sweeps.
std::vector<std::string> Contents(Store& store) {
  std::vector<std::string> contents;
  absl::StatusOr<std::vector<RunRecord>> runs = store.runs().ListRuns();
  EXPECT_TRUE(runs.ok()) << runs.status();
  for (const RunRecord& run : runs.ok() ? *runs : std::vector<RunRecord>{}) {
    contents.push_back(absl::StrCat(run.id, " ", NameOf(kRunStateNames, run.state), " ",
                                    run.sweep_id, " ", run.trial.value_or(-1), " ",
                                    run.progress.timesteps, " ", run.submission.request_id));
  }
  absl::StatusOr<std::vector<SweepRecord>> sweeps = store.sweeps().ListSweeps();
  EXPECT_TRUE(sweeps.ok()) << sweeps.status();
  for (const SweepRecord& sweep : sweeps.ok() ? *sweeps : std::vector<SweepRecord>{}) {
    contents.push_back(absl::StrCat(sweep.id, " ", sweep.name, " ", sweep.trials.size(), " ",
                                    NameOf(kSweepStateNames, sweep.state)));
  }
  return contents;
}

TEST_F(SweepStoreTest, ABackupIsTheStoreAsItWasAndOpensAsIt) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("s", 3, 2), kStart).ok());
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("t", 1, 1), kStart).ok());
  absl::StatusOr<std::optional<LearnerLease>> lease =
      store->runs().AcquireRun("L", "a", "N", kStart);
  ASSERT_TRUE(lease.ok() && lease->has_value());
  ASSERT_TRUE(store->runs().ReportProgress((*lease)->key, {.timesteps = 400}, kStart).ok());
  const std::vector<std::string> before = Contents(*store);

  absl::StatusOr<BackupCounts> counts = store->Backup(Path("backup.db"));
  ASSERT_TRUE(counts.ok()) << counts.status();
  EXPECT_EQ(counts->runs, 7);
  EXPECT_EQ(counts->sweeps, 2);
  EXPECT_EQ(counts->studies, 0);
  // The store goes on; the backup does not.
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("later", 1, 1), kStart).ok());

  absl::StatusOr<std::unique_ptr<Store>> restored =
      Store::Open(Path("backup.db"), {.lease_duration = absl::Seconds(10)}, kStart);
  ASSERT_TRUE(restored.ok()) << restored.status();
  EXPECT_EQ(Contents(**restored), before);
  EXPECT_THAT(before, ::testing::Contains(HasSubstr("run-1 running sweep-1 0 400")));
  // Nothing but the backup was written beside it.
  restored->reset();
  EXPECT_FALSE(std::filesystem::exists(Path(absl::StrCat("backup.db.tmp.", ::getpid()))));
}

// A directory at `path` that Backup may not write in (`read_only`: read-only to its owner, or
// for root, whom modes do not stop, a read-only tmpfs), or that holds `bytes` at most (a tmpfs:
// root only). Unmounted and writable again when destroyed.
class SmallDirectory {
 public:
  SmallDirectory(const std::string& path, bool read_only, int bytes) : path_(path) {
    std::filesystem::create_directories(path);
    if (::geteuid() != 0) {
      if (read_only) ::chmod(path.c_str(), 0500);
      usable_ = read_only;
      return;
    }
    const std::string options = absl::StrCat("size=", bytes);
    mounted_ = ::mount("dcs-test", path.c_str(), "tmpfs", read_only ? MS_RDONLY : 0,
                       options.c_str()) == 0;
    usable_ = mounted_;
    if (!mounted_) why_ = std::strerror(errno);
  }
  ~SmallDirectory() {
    if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
    ::chmod(path_.c_str(), 0700);
  }
  bool usable() const { return usable_; }
  const std::string& why() const { return why_; }

 private:
  const std::string path_;
  bool mounted_ = false;
  bool usable_ = false;
  std::string why_ = "a full disk needs a tmpfs, which needs root";
};

TEST_F(SweepStoreTest, ABackupWhereItCannotBeWrittenFailsNamingItAndLeavesNothing) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->sweeps().SubmitSweep(Sweep("s", 100, 10), kStart).ok());  // over 64 KiB
  const std::string missing = Path("missing/backup.db");
  EXPECT_EQ(store->Backup(missing).status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(store->Backup(missing).status().message(), HasSubstr(missing));

  SmallDirectory locked(Path("locked"), /*read_only=*/true, 1 << 20);
  ASSERT_TRUE(locked.usable()) << locked.why();
  absl::Status refused = store->Backup(Path("locked/backup.db")).status();
  EXPECT_EQ(refused.code(), absl::StatusCode::kPermissionDenied) << refused;
  EXPECT_THAT(refused.message(), HasSubstr(Path("locked/backup.db")));
  EXPECT_TRUE(std::filesystem::is_empty(Path("locked")));

  SmallDirectory full(Path("full"), /*read_only=*/false, 64 << 10);
  if (!full.usable()) GTEST_SKIP() << full.why();
  absl::Status exhausted = store->Backup(Path("full/backup.db")).status();
  EXPECT_EQ(exhausted.code(), absl::StatusCode::kResourceExhausted) << exhausted;
  EXPECT_THAT(exhausted.message(), HasSubstr(Path("full/backup.db")));
  EXPECT_TRUE(std::filesystem::is_empty(Path("full")));
  // The store is as it was.
  EXPECT_EQ(store->runs().ListRuns()->size(), 1000u);
}

TEST(SweepStateTest, DerivesFromItsRuns) {
  using S = RunState;
  auto state = [](std::vector<std::pair<RunState, int64_t>> runs, bool cancelled,
                  bool open = false) { return SweepStateOf(runs, cancelled, open); };
  EXPECT_EQ(state({{S::kQueued, 4}}, false), SweepState::kQueued);
  EXPECT_EQ(state({{S::kQueued, 3}, {S::kCompleted, 1}}, false), SweepState::kRunning);
  EXPECT_EQ(state({{S::kRunning, 1}, {S::kFailed, 1}}, true), SweepState::kRunning);
  EXPECT_EQ(state({{S::kCompleted, 3}, {S::kFailed, 1}}, false), SweepState::kFailed);
  EXPECT_EQ(state({{S::kCompleted, 3}, {S::kCancelled, 1}}, true), SweepState::kCancelled);
  EXPECT_EQ(state({{S::kCompleted, 4}}, false), SweepState::kCompleted);
  // An open study sweep: queued until a run starts, then running until it closes.
  EXPECT_EQ(state({}, false, true), SweepState::kQueued);
  EXPECT_EQ(state({{S::kQueued, 4}}, false, true), SweepState::kQueued);
  EXPECT_EQ(state({{S::kCompleted, 4}}, false, true), SweepState::kRunning);
  EXPECT_EQ(state({{S::kCompleted, 3}, {S::kFailed, 1}}, false, true), SweepState::kRunning);
}

}  // namespace
}  // namespace dcs::coordinator
