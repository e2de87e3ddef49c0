// Copyright 2026 The DCS Authors.
//
// Ended runs and sweeps removed for good (coordinator/run_removal.h) from a real SQLite store and
// its data directory: everything of theirs goes, in one transaction, and nothing else; what still
// works is refused, all of a list or none; a removal cut short between the store and the files
// leaves directories that the next start removes.

#include <SQLiteCpp/Database.h>

#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "coordinator/run_removal.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/coordinator/study_sweep_fixture.h"

namespace dcs::coordinator {
namespace {

namespace fs = std::filesystem;

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::UnorderedElementsAre;

RunSubmission Alone(const std::string& request_id) {
  return {.request_id = request_id, .config = "env: cartpole\n", .seed = 3, .env = "cartpole",
          .n_envs = 2, .total_timesteps = 1000};
}

// A plain sweep of two trials and one seed.
SweepSubmission PlainSweep(const std::string& request_id) {
  SweepSubmission sweep{.request_id = request_id, .name = "grid", .spec = "conditions: []\n",
                        .seeds = 1};
  for (int trial = 0; trial < 2; ++trial) {
    sweep.trials.push_back({.condition = absl::StrCat("c", trial), .family = "static",
                            .observe = "none"});
    sweep.runs.push_back({.trial = trial, .run = Alone(absl::StrCat(request_id, "/", trial))});
  }
  return sweep;
}

class RunRemovalTest : public StudySweepFixture {
 protected:
  std::string Data() { return Path("data"); }

  // A run's directory with a file in it, as SubmitRun's handler and a learner leave one.
  void WriteRunDirectory(const std::string& run_id) {
    const std::string dir = RunDirectory(Data(), run_id);
    fs::create_directories(dir + "/checkpoints");
    ASSERT_TRUE(WriteFileAtomically(dir + "/config.yaml", "env: cartpole\n").ok());
  }
  bool HasDirectory(const std::string& run_id) {
    return fs::exists(RunDirectory(Data(), run_id));
  }

  // Rows of `table` whose `column` is `number`, read past the store.
  int64_t Rows(const std::string& table, const std::string& column, int64_t number) {
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READONLY);
    SQLite::Statement count(db, absl::StrCat("SELECT count(*) FROM ", table, " WHERE ", column,
                                             " = ?"));
    count.bind(1, number);
    count.executeStep();
    return count.getColumn(0).getInt64();
  }

  // run-<number>'s rows in every table that holds a run's.
  int64_t RunRows(int64_t number) {
    int64_t rows = Rows("runs", "number", number);
    for (const char* table : {"leases", "checkpoints", "evaluations", "evaluation_jobs",
                              "evaluation_returns", "grid_evaluations"}) {
      rows += Rows(table, "run", number);
    }
    return rows;
  }

  // Submits a run alone, leases it, records a checkpoint and an evaluation with its results,
  // and finishes it as `state`; returns its lease.
  LeaseKey TrainAlone(const std::string& request_id, RunState state) {
    EXPECT_TRUE(store_->runs().SubmitRun(Alone(request_id), kNow).ok());
    const LeaseKey key = Lease();
    WriteRunDirectory(key.run_id);
    EXPECT_TRUE(store_->checkpoints()
                    .RecordCheckpoint(key, {"000000000256", 256, "abc"}, std::nullopt, kNow)
                    .ok());
    EXPECT_TRUE(store_->evaluations()
                    .SubmitEvaluation(key, {.policy_version = 1, .step = 256, .contexts = 1,
                                            .episodes = 1, .weights = "w"},
                                      kNow)
                    .ok());
    ReportEveryOpenJob();
    EXPECT_TRUE(store_->runs().FinishRun(key, state, "", kNow).ok());
    return key;
  }

  // An actor evaluates every open evaluation job.
  void ReportEveryOpenJob() {
    absl::StatusOr<std::optional<EvaluationGrant>> grant =
        store_->evaluations().AcquireEvaluationJobs("actor", "n", 100, 1, true, kNow);
    ASSERT_TRUE(grant.ok()) << grant.status();
    if (!grant->has_value()) return;
    std::vector<JobResult> results;
    for (const EvaluationJobKey& job : (*grant)->jobs) {
      results.push_back({.job = job, .result = {.returns = {1.0}, .seconds = 0.1}});
    }
    ASSERT_TRUE(store_->evaluations().ReportEvaluationJobs(results).ok());
  }

  // A grid evaluation of `run_id` with `cells` cells.
  void SubmitGrid(const std::string& run_id, int cells) {
    ASSERT_TRUE(store_->evaluations()
                    .SubmitGridEvaluation({.request_id = "grid-" + run_id, .run_id = run_id,
                                           .cells = cells, .episodes = 1, .grid = "g",
                                           .weights = "w"},
                                          kNow)
                    .ok());
  }
};

TEST_F(RunRemovalTest, AnEndedRunGoesWithEveryRowAndItsDirectoryAndNothingElse) {
  TrainAlone("a", RunState::kCompleted);
  SubmitGrid("run-1", 2);
  ReportEveryOpenJob();
  ASSERT_TRUE(store_->runs().SubmitRun(Alone("b"), kNow).ok());
  WriteRunDirectory("run-2");
  ASSERT_GT(RunRows(1), 4);

  absl::StatusOr<RunRemoval> removal = RemoveRuns(*store_, Data(), {"run-1"});
  ASSERT_TRUE(removal.ok()) << removal.status();
  ASSERT_EQ(removal->runs.size(), 1u);
  EXPECT_EQ(removal->runs[0].id, "run-1");
  EXPECT_EQ(removal->runs[0].state, RunState::kCompleted);
  EXPECT_EQ(removal->runs[0].checkpoint, "000000000256");
  EXPECT_TRUE(removal->files.ok()) << removal->files;

  EXPECT_EQ(RunRows(1), 0);
  EXPECT_FALSE(HasDirectory("run-1"));
  EXPECT_EQ(store_->runs().GetRun("run-1").status().code(), absl::StatusCode::kNotFound);
  // The other run keeps its row, leases and directory; the counts no longer hold run-1.
  EXPECT_EQ(Rows("leases", "run", 2), 3);
  EXPECT_TRUE(HasDirectory("run-2"));
  absl::StatusOr<StoreCounts> counts = store_->Counts();
  ASSERT_TRUE(counts.ok()) << counts.status();
  for (const auto& [state, runs] : counts->runs_by_state) {
    EXPECT_EQ(runs, state == RunState::kQueued ? 1 : 0) << NameOf(kRunStateNames, state);
  }
  // Its id is never given again.
  absl::StatusOr<RunRecord> next = store_->runs().SubmitRun(Alone("c"), kNow);
  ASSERT_TRUE(next.ok()) << next.status();
  EXPECT_EQ(next->id, "run-3");
}

TEST_F(RunRemovalTest, ARunThatStillWorksIsRefusedAndNothingOfTheListGoes) {
  TrainAlone("a", RunState::kFailed);
  ASSERT_TRUE(store_->runs().SubmitRun(Alone("b"), kNow).ok());
  WriteRunDirectory("run-2");

  absl::StatusOr<RunRemoval> queued = RemoveRuns(*store_, Data(), {"run-1", "run-2"});
  EXPECT_EQ(queued.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(queued.status().message(),
            "run-2 is queued: stop it first with `dcs runs cancel run-2`");
  Lease();
  EXPECT_THAT(RemoveRuns(*store_, Data(), {"run-2"}).status().message(),
              HasSubstr("run-2 is running"));
  EXPECT_EQ(RemoveRuns(*store_, Data(), {"run-1", "run-7"}).status().code(),
            absl::StatusCode::kNotFound);
  EXPECT_EQ(RemoveRuns(*store_, Data(), {}).status().code(), absl::StatusCode::kInvalidArgument);
  // None of them went.
  EXPECT_TRUE(store_->runs().GetRun("run-1").ok());
  EXPECT_TRUE(HasDirectory("run-1"));
  EXPECT_TRUE(HasDirectory("run-2"));

  // Cancelled, it goes; a run named twice goes once.
  ASSERT_TRUE(store_->runs().CancelRun("run-2", kNow).ok());
  absl::StatusOr<RunRemoval> removal = RemoveRuns(*store_, Data(), {"run-2", "run-1", "run-2"});
  ASSERT_TRUE(removal.ok()) << removal.status();
  ASSERT_EQ(removal->runs.size(), 2u);
  EXPECT_EQ(removal->runs[0].id, "run-2");
  EXPECT_EQ(removal->runs[1].id, "run-1");
  EXPECT_TRUE(store_->runs().ListRuns()->empty());
}

TEST_F(RunRemovalTest, AGridEvaluationStillOpenHoldsItsRun) {
  TrainAlone("a", RunState::kCompleted);
  SubmitGrid("run-1", 3);
  EXPECT_EQ(RemoveRuns(*store_, Data(), {"run-1"}).status().message(),
            "run-1 has a grid evaluation (`dcs eval --on-actors`) with 3 cells still to "
            "evaluate: remove it once they are in");
  ReportEveryOpenJob();
  EXPECT_TRUE(RemoveRuns(*store_, Data(), {"run-1"}).ok());
}

TEST_F(RunRemovalTest, ASweepsRunGoesOnlyWithItsSweep) {
  ASSERT_TRUE(store_->sweeps().SubmitSweep(PlainSweep("s"), kNow).ok());
  ASSERT_TRUE(store_->sweeps().CancelSweep("sweep-1", kNow).ok());
  EXPECT_EQ(RemoveRuns(*store_, Data(), {"run-1"}).status().message(),
            "run-1 belongs to sweep-1, whose report needs all its runs: remove the sweep with "
            "`dcs sweeps rm sweep-1`");
  EXPECT_TRUE(store_->runs().GetRun("run-1").ok());
}

TEST_F(RunRemovalTest, AnEndedSweepGoesWithItsTrialsAndRunsAndNothingElse) {
  ASSERT_TRUE(store_->sweeps().SubmitSweep(PlainSweep("s"), kNow).ok());
  ASSERT_TRUE(store_->sweeps().SubmitSweep(PlainSweep("t"), kNow).ok());
  for (const char* run_id : {"run-1", "run-2", "run-3", "run-4"}) WriteRunDirectory(run_id);
  // Running: refused, naming what runs and how to stop it.
  Train({{1000, 10.0}}, /*finish=*/true);  // run-1
  const absl::StatusOr<SweepRemoval> running = RemoveSweeps(*store_, Data(), {"sweep-1"});
  EXPECT_EQ(running.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(running.status().message(),
            "sweep-1 is running (1 of its runs queued or running): stop it first with "
            "`dcs sweeps cancel sweep-1`");
  ASSERT_TRUE(store_->sweeps().CancelSweep("sweep-1", kNow).ok());
  EXPECT_EQ(RemoveSweeps(*store_, Data(), {"sweep-1", "sweep-2"}).status().code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_TRUE(store_->sweeps().GetSweep("sweep-1").ok());
  EXPECT_EQ(RemoveSweeps(*store_, Data(), {"sweep-9"}).status().code(),
            absl::StatusCode::kNotFound);

  absl::StatusOr<SweepRemoval> removal = RemoveSweeps(*store_, Data(), {"sweep-1"});
  ASSERT_TRUE(removal.ok()) << removal.status();
  ASSERT_EQ(removal->sweeps.size(), 1u);
  EXPECT_EQ(removal->sweeps[0].sweep.id, "sweep-1");
  EXPECT_EQ(removal->sweeps[0].sweep.state, SweepState::kCancelled);
  ASSERT_EQ(removal->sweeps[0].runs.size(), 2u);
  EXPECT_EQ(removal->sweeps[0].runs[0].state, RunState::kCompleted);
  EXPECT_EQ(removal->sweeps[0].runs[1].state, RunState::kCancelled);
  EXPECT_TRUE(removal->files.ok()) << removal->files;

  EXPECT_EQ(store_->sweeps().GetSweep("sweep-1").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(Rows("trials", "sweep", 1), 0);
  EXPECT_EQ(RunRows(1) + RunRows(2), 0);
  EXPECT_FALSE(HasDirectory("run-1"));
  EXPECT_FALSE(HasDirectory("run-2"));
  // The other sweep is whole; no sweep id is given again.
  ASSERT_TRUE(store_->sweeps().GetSweep("sweep-2").ok());
  EXPECT_EQ(store_->sweeps().ListSweepRuns("sweep-2")->size(), 2u);
  EXPECT_TRUE(HasDirectory("run-3"));
  absl::StatusOr<SweepRecord> next = store_->sweeps().SubmitSweep(PlainSweep("u"), kNow);
  ASSERT_TRUE(next.ok()) << next.status();
  EXPECT_EQ(next->id, "sweep-3");
}

TEST_F(RunRemovalTest, AStudySweepGoesWithItsStudyOnceItAddsNoMoreTrials) {
  const SweepRecord sweep = Submit(kSpec);
  Advance(sweep.id);
  Train({{1000, 10.0}, {2000, 12.0}}, /*finish=*/true);
  ASSERT_FALSE(Trials(sweep).empty());
  ASSERT_GT(Rows("study_trial_values", "study", 1), 0);
  ASSERT_TRUE(store_->sweeps().CancelSweep(sweep.id, kNow).ok());

  absl::StatusOr<SweepRemoval> removal = RemoveSweeps(*store_, Data(), {sweep.id});
  ASSERT_TRUE(removal.ok()) << removal.status();
  EXPECT_EQ(removal->sweeps[0].sweep.study_id, sweep.study_id);
  EXPECT_EQ(store_->studies().GetStudy(sweep.study_id).status().code(),
            absl::StatusCode::kNotFound);
  for (const char* table : {"study_trials", "study_trial_values", "study_trial_reports",
                            "study_trial_rungs"}) {
    EXPECT_EQ(Rows(table, "study", 1), 0) << table;
  }
  EXPECT_EQ(Rows("studies", "number", 1), 0);
}

TEST_F(RunRemovalTest, AnOpenStudySweepIsRefusedThoughNoRunIsGoing) {
  const SweepRecord sweep = Submit(kSpec);
  const absl::StatusOr<SweepRemoval> removal = RemoveSweeps(*store_, Data(), {sweep.id});
  EXPECT_EQ(removal.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(removal.status().message(), HasSubstr("its study asking for more"));
  EXPECT_TRUE(store_->studies().GetStudy(sweep.study_id).ok());
}

TEST_F(RunRemovalTest, DirectoriesLeftByARemovalCutShortGoAtTheNextStart) {
  TrainAlone("a", RunState::kCompleted);
  TrainAlone("b", RunState::kCompleted);
  // The store's part alone, as when the coordinator dies before the files go.
  ASSERT_TRUE(store_->runs().DeleteRuns({"run-1"}).ok());
  ASSERT_TRUE(HasDirectory("run-1"));
  // Not a removed run's: a run's the store never gave (its backup is older), a name of no run, a
  // file.
  WriteRunDirectory("run-9");
  fs::create_directories(Data() + "/runs/notes");
  ASSERT_TRUE(WriteFileAtomically(Data() + "/runs/run-1.txt", "").ok());

  absl::StatusOr<std::vector<std::string>> removed = RemoveLeftoverRunDirectories(*store_, Data());
  ASSERT_TRUE(removed.ok()) << removed.status();
  EXPECT_THAT(*removed, ElementsAre("run-1"));
  EXPECT_FALSE(HasDirectory("run-1"));
  std::vector<std::string> kept;
  for (const fs::directory_entry& entry : fs::directory_iterator(Data() + "/runs")) {
    kept.push_back(entry.path().filename().string());
  }
  EXPECT_THAT(kept, UnorderedElementsAre("run-2", "run-9", "notes", "run-1.txt"));
  // With nothing left, nothing more goes; a data directory without runs is fine.
  EXPECT_TRUE(RemoveLeftoverRunDirectories(*store_, Data())->empty());
  EXPECT_TRUE(RemoveLeftoverRunDirectories(*store_, Path("empty"))->empty());
}

}  // namespace
}  // namespace dcs::coordinator
