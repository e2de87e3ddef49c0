// Copyright 2026 The DCS Authors.
#include "coordinator/store.h"

#include <SQLiteCpp/Database.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "coordinator/run_state.h"
#include "coordinator/store_schema.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const absl::Time kStart = absl::FromUnixSeconds(1'800'000'000);
const absl::Duration kLease = absl::Seconds(10);

RunSubmission Submission(std::string request_id, int n_envs = 2) {
  return {.request_id = std::move(request_id),
          .config = "env: cartpole\n",
          .seed = 7,
          .env = "cartpole",
          .n_envs = n_envs,
          .total_timesteps = 1000};
}

class RunStoreTest : public testing::TempDirTest {
 protected:
  std::unique_ptr<Store> Open(absl::Time now = kStart) {
    absl::StatusOr<std::unique_ptr<Store>> store =
        Store::Open(Path("coordinator.db"), {.lease_duration = kLease}, now);
    EXPECT_TRUE(store.ok()) << store.status();
    return store.ok() ? *std::move(store) : nullptr;
  }

  // Submits a run and leases it to learner "L" with fingerprint "N".
  LearnerLease SubmitAndAcquire(Store& store, std::string request_id = "request-1") {
    EXPECT_TRUE(store.runs().SubmitRun(Submission(std::move(request_id)), kStart).ok());
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store.runs().AcquireRun("L", "127.0.0.1:5000", "N", kStart);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? **lease : LearnerLease{};
  }
};

TEST_F(RunStoreTest, SubmittingIsIdempotentByRequestId) {
  std::unique_ptr<Store> store = Open();
  absl::StatusOr<RunRecord> first = store->runs().SubmitRun(Submission("request-1"), kStart);
  absl::StatusOr<RunRecord> again = store->runs().SubmitRun(Submission("request-1"), kStart);
  absl::StatusOr<RunRecord> other = store->runs().SubmitRun(Submission("request-2"), kStart);
  ASSERT_TRUE(first.ok() && again.ok() && other.ok());
  EXPECT_EQ(first->id, "run-1");
  EXPECT_EQ(again->id, "run-1");
  EXPECT_EQ(other->id, "run-2");
  EXPECT_EQ(first->state, RunState::kQueued);
  EXPECT_EQ(first->submission.seed, 7u);
  absl::StatusOr<std::vector<RunRecord>> runs = store->runs().ListRuns();
  ASSERT_TRUE(runs.ok());
  EXPECT_EQ(runs->size(), 2u);
}

TEST_F(RunStoreTest, RejectsASubmissionWithoutRequestIdOrSlots) {
  std::unique_ptr<Store> store = Open();
  EXPECT_EQ(store->runs().SubmitRun(Submission(""), kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(store->runs().SubmitRun(Submission("r", /*n_envs=*/0), kStart).status().message(),
              HasSubstr("n_envs is 0"));
}

TEST_F(RunStoreTest, UnknownRunsAreNotFound) {
  std::unique_ptr<Store> store = Open();
  EXPECT_EQ(store->runs().GetRun("run-9").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(store->runs().GetRun("nonsense").status().code(), absl::StatusCode::kNotFound);
}

TEST_F(RunStoreTest, ALearnerTakesTheOldestQueuedRun) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease lease = SubmitAndAcquire(*store);
  EXPECT_EQ(lease.key.run_id, "run-1");
  EXPECT_EQ(lease.key.slot, kLearnerSlot);
  EXPECT_EQ(lease.key.epoch, 1);
  EXPECT_EQ(lease.run.state, RunState::kRunning);
  EXPECT_EQ(lease.run.learner_numerics, "N");
  // Nothing else is queued.
  absl::StatusOr<std::optional<LearnerLease>> none =
      store->runs().AcquireRun("L2", "a", "N", kStart);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
}

TEST_F(RunStoreTest, SlotsGoToActorsOnlyOnceALearnerHoldsTheRun) {
  std::unique_ptr<Store> store = Open();
  ASSERT_TRUE(store->runs().SubmitRun(Submission("request-1"), kStart).ok());
  absl::StatusOr<std::optional<SlotLease>> early = store->runs().AcquireSlot("A", "N", {}, kStart);
  ASSERT_TRUE(early.ok());
  EXPECT_FALSE(early->has_value());

  const LearnerLease learner = SubmitAndAcquire(*store, "request-1");
  absl::StatusOr<std::optional<SlotLease>> slot0 = store->runs().AcquireSlot("A", "N", {}, kStart);
  absl::StatusOr<std::optional<SlotLease>> slot1 = store->runs().AcquireSlot("B", "N", {}, kStart);
  absl::StatusOr<std::optional<SlotLease>> none = store->runs().AcquireSlot("C", "N", {}, kStart);
  ASSERT_TRUE(slot0.ok() && slot0->has_value() && slot1.ok() && slot1->has_value() && none.ok());
  EXPECT_EQ((*slot0)->key.slot, 0);
  EXPECT_EQ((*slot1)->key.slot, 1);
  EXPECT_EQ((*slot0)->learner_address, "127.0.0.1:5000");
  EXPECT_EQ((*slot0)->learner_epoch, learner.key.epoch);
  EXPECT_EQ((*slot0)->seed, 7u);
  EXPECT_FALSE(none->has_value());
}

TEST_F(RunStoreTest, WorkersWithOtherNumericLibrariesGetNoLeaseOfTheRun) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease learner = SubmitAndAcquire(*store);
  // The first actor pins the run's actor numerics; one with others gets nothing.
  absl::StatusOr<std::optional<SlotLease>> first = store->runs().AcquireSlot("A", "E", {}, kStart);
  ASSERT_TRUE(first.ok() && first->has_value());
  absl::StatusOr<std::optional<SlotLease>> other = store->runs().AcquireSlot("B", "F", {}, kStart);
  EXPECT_EQ(other.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(other.status().message(),
            "run-1 computes with \"E\"; this worker with \"F\": a run never mixes numeric "
            "libraries");
  absl::StatusOr<std::optional<SlotLease>> same = store->runs().AcquireSlot("C", "E", {}, kStart);
  ASSERT_TRUE(same.ok());
  EXPECT_TRUE(same->has_value());
  EXPECT_EQ(store->runs().GetRun("run-1")->actor_numerics, "E");
  // Nor can a learner with other numerics take the run back.
  ASSERT_TRUE(store->runs().ReleaseLease(learner.key, kStart).ok());
  absl::StatusOr<std::optional<LearnerLease>> refused =
      store->runs().AcquireRun("L2", "b", "M", kStart);
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(refused.status().message(), HasSubstr("run-1 computes with \"N\""));
  absl::StatusOr<std::optional<LearnerLease>> taken =
      store->runs().AcquireRun("L2", "b", "N", kStart);
  ASSERT_TRUE(taken.ok());
  EXPECT_TRUE(taken->has_value());
}

TEST_F(RunStoreTest, AnActorSkipsTheRunsOfLearnersItWasToldAreCompleteButNotTheirNextLearner) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease first = SubmitAndAcquire(*store);
  const LeaseKey complete = first.key;
  // Another run's learner, or another epoch of this one's, is not this learner.
  const LeaseKey others[] = {{.run_id = "run-2", .slot = kLearnerSlot, .epoch = 1},
                             {.run_id = "run-1", .slot = kLearnerSlot, .epoch = 2}};
  absl::StatusOr<std::optional<SlotLease>> slot =
      store->runs().AcquireSlot("A", "N", others, kStart);
  ASSERT_TRUE(slot.ok() && slot->has_value()) << slot.status();
  slot = store->runs().AcquireSlot("A", "N", {&complete, 1}, kStart);
  ASSERT_TRUE(slot.ok());
  EXPECT_FALSE(slot->has_value());

  // The learner dies before ending the run; the next one needs the slots.
  const absl::Time later = kStart + absl::Seconds(30);
  absl::StatusOr<std::optional<LearnerLease>> second =
      store->runs().AcquireRun("L2", "b", "N", later);
  ASSERT_TRUE(second.ok() && second->has_value());
  slot = store->runs().AcquireSlot("A", "N", {&complete, 1}, later);
  ASSERT_TRUE(slot.ok() && slot->has_value()) << slot.status();
  EXPECT_EQ((*slot)->learner_epoch, 2);
}

TEST_F(RunStoreTest, ALapsedLeaseGoesBackToTheQueueAndItsOldHolderIsRefused) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease first = SubmitAndAcquire(*store);
  absl::StatusOr<std::optional<SlotLease>> slot = store->runs().AcquireSlot("A", "N", {}, kStart);
  ASSERT_TRUE(slot.ok() && slot->has_value());

  // Renewed in time: still held.
  ASSERT_TRUE(store->runs().RenewLease(first.key, kStart + absl::Seconds(5)).ok());
  absl::StatusOr<int> lapsed = store->ExpireLeases(kStart + absl::Seconds(12));
  ASSERT_TRUE(lapsed.ok());
  EXPECT_EQ(*lapsed, 1);  // the slot's; the learner renewed
  // The learner stops renewing.
  const absl::Time later = kStart + absl::Seconds(30);
  lapsed = store->ExpireLeases(later);
  ASSERT_TRUE(lapsed.ok());
  EXPECT_EQ(*lapsed, 1);
  EXPECT_EQ(store->runs().GetRun("run-1")->state, RunState::kQueued);
  absl::Status stale = store->runs().RenewLease(first.key, later);
  EXPECT_EQ(stale.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(stale.message(), HasSubstr("lapsed"));

  absl::StatusOr<std::optional<LearnerLease>> second =
      store->runs().AcquireRun("L2", "b", "N", later);
  ASSERT_TRUE(second.ok() && second->has_value());
  EXPECT_EQ((*second)->key.epoch, 2);
  EXPECT_EQ(store->LeasesLapsed(), 2);
  stale = store->runs().ReportProgress(first.key, {.timesteps = 5}, later);
  EXPECT_EQ(stale.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(stale.message(), HasSubstr("moved: epoch 2 was granted after epoch 1"));
  EXPECT_EQ(store->runs().RenewLease((*slot)->key, later).code(),
            absl::StatusCode::kFailedPrecondition);
}

// Under load the workers' Acquire calls, which expire lapsed leases first, find nearly every
// lapse before the coordinator's reaper does; the count must include those.
TEST_F(RunStoreTest, LapsesFoundByAnAcquireAreCountedOnce) {
  std::unique_ptr<Store> store = Open();
  SubmitAndAcquire(*store);
  ASSERT_TRUE(store->runs().AcquireSlot("A", "N", {}, kStart).ok());
  EXPECT_EQ(store->LeasesLapsed(), 0);
  const absl::Time later = kStart + absl::Seconds(30);
  // The learner's lease lapsed (A's slot lease goes with it: the run is queued again).
  ASSERT_TRUE(store->runs().AcquireSlot("B", "N", {}, later).ok());
  EXPECT_EQ(store->LeasesLapsed(), 1);
  absl::StatusOr<int> lapsed = store->ExpireLeases(later);
  ASSERT_TRUE(lapsed.ok());
  EXPECT_EQ(*lapsed, 0);
  EXPECT_EQ(store->LeasesLapsed(), 1);
}

TEST_F(RunStoreTest, ANewLearnerLeaseFreesTheSlotLeases) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease first = SubmitAndAcquire(*store);
  absl::StatusOr<std::optional<SlotLease>> slot = store->runs().AcquireSlot("A", "N", {}, kStart);
  ASSERT_TRUE(slot.ok() && slot->has_value());
  ASSERT_TRUE(store->runs().ReleaseLease(first.key, kStart).ok());
  EXPECT_EQ(store->runs().GetRun("run-1")->state, RunState::kQueued);
  absl::StatusOr<std::optional<LearnerLease>> second =
      store->runs().AcquireRun("L2", "b", "N", kStart);
  ASSERT_TRUE(second.ok() && second->has_value());
  EXPECT_EQ(store->runs().RenewLease((*slot)->key, kStart).code(),
            absl::StatusCode::kFailedPrecondition);
  absl::StatusOr<std::optional<SlotLease>> again = store->runs().AcquireSlot("A", "N", {}, kStart);
  ASSERT_TRUE(again.ok() && again->has_value());
  EXPECT_EQ((*again)->key.slot, 0);
  EXPECT_EQ((*again)->key.epoch, 2);
  EXPECT_EQ((*again)->learner_address, "b");
}

TEST_F(RunStoreTest, ProgressAndCheckpointsAreRecorded) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease lease = SubmitAndAcquire(*store);
  ASSERT_TRUE(store->runs()
                  .ReportProgress(lease.key,
                                  {.timesteps = 256,
                                   .policy_version = 2,
                                   .steps_per_second = 1000,
                                   .recent_return = 21.5,
                                   .avg_combined = 42.25,
                                   .evaluation_step = 200},
                                  kStart)
                  .ok());
  ASSERT_TRUE(
      store->checkpoints()
          .RecordCheckpoint(lease.key, {"000000000256", 256, "abc"}, std::nullopt, kStart)
          .ok());
  absl::StatusOr<RunRecord> run = store->runs().GetRun("run-1");
  ASSERT_TRUE(run.ok());
  EXPECT_EQ(run->progress.timesteps, 256);
  EXPECT_EQ(run->progress.policy_version, 2);
  EXPECT_EQ(run->progress.recent_return, 21.5);
  EXPECT_EQ(run->progress.avg_combined, 42.25);
  EXPECT_EQ(run->progress.evaluation_step, 200);
  EXPECT_EQ(run->checkpoint, "000000000256");
  absl::StatusOr<std::vector<CheckpointRecord>> checkpoints =
      store->checkpoints().ListCheckpoints("run-1");
  ASSERT_TRUE(checkpoints.ok());
  ASSERT_EQ(checkpoints->size(), 1u);
  EXPECT_EQ((*checkpoints)[0].sha256, "abc");
}

TEST_F(RunStoreTest, AFinishedRunVoidsItsLeases) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease lease = SubmitAndAcquire(*store);
  ASSERT_TRUE(store->runs().FinishRun(lease.key, RunState::kCompleted, "", kStart).ok());
  EXPECT_EQ(store->runs().GetRun("run-1")->state, RunState::kCompleted);
  absl::Status late = store->runs().RenewLease(lease.key, kStart);
  EXPECT_EQ(late.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(late.message(), HasSubstr("the run is completed"));
  EXPECT_EQ(store->runs().CancelRun("run-1", kStart).status().code(),
            absl::StatusCode::kFailedPrecondition);
}

TEST_F(RunStoreTest, CancellingARunFreesItsLeases) {
  std::unique_ptr<Store> store = Open();
  const LearnerLease lease = SubmitAndAcquire(*store);
  absl::StatusOr<RunRecord> cancelled = store->runs().CancelRun("run-1", kStart);
  ASSERT_TRUE(cancelled.ok());
  EXPECT_EQ(cancelled->state, RunState::kCancelled);
  EXPECT_THAT(store->runs().RenewLease(lease.key, kStart).message(), HasSubstr("cancelled"));
  absl::StatusOr<std::optional<SlotLease>> slot = store->runs().AcquireSlot("A", "N", {}, kStart);
  ASSERT_TRUE(slot.ok());
  EXPECT_FALSE(slot->has_value());
}

TEST_F(RunStoreTest, EverythingSurvivesAReopenAndHoldersGetAFullLease) {
  LeaseKey key;
  {
    std::unique_ptr<Store> store = Open();
    key = SubmitAndAcquire(*store).key;
    ASSERT_TRUE(
        store->checkpoints()
            .RecordCheckpoint(key, {"000000000256", 256, "abc"}, std::nullopt, kStart)
            .ok());
  }
  // The coordinator was down for longer than a lease.
  const absl::Time restart = kStart + absl::Seconds(60);
  std::unique_ptr<Store> store = Open(restart);
  EXPECT_EQ(store->runs().GetRun("run-1")->state, RunState::kRunning);
  EXPECT_EQ(store->runs().GetRun("run-1")->checkpoint, "000000000256");
  EXPECT_TRUE(store->runs().RenewLease(key, restart + absl::Seconds(9)).ok());
}

TEST_F(RunStoreTest, RefusesADatabaseOfANewerSchema) {
  Open();
  {
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE);
    db.exec("PRAGMA user_version = " + std::to_string(CurrentSchemaVersion() + 1));
  }
  absl::StatusOr<std::unique_ptr<Store>> store =
      Store::Open(Path("coordinator.db"), {.lease_duration = kLease}, kStart);
  EXPECT_EQ(store.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(store.status().message(), HasSubstr("newer DCS"));
}

TEST_F(RunStoreTest, RefusesADatabaseOfANegativeSchemaVersionAsCorrupt) {
  Open();
  {
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE);
    db.exec("PRAGMA user_version = -251");
  }
  absl::StatusOr<std::unique_ptr<Store>> store =
      Store::Open(Path("coordinator.db"), {.lease_duration = kLease}, kStart);
  EXPECT_EQ(store.status().code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(store.status().message(), HasSubstr("coordinator.db is corrupt"));
  EXPECT_THAT(store.status().message(), HasSubstr("schema version -251"));
}

TEST_F(RunStoreTest, CountsRunsByStateAndWaitingWork) {
  std::unique_ptr<Store> store = Open();
  SubmitAndAcquire(*store);
  ASSERT_TRUE(store->runs().SubmitRun(Submission("request-2"), kStart).ok());
  absl::StatusOr<StoreCounts> counts = store->Counts();
  ASSERT_TRUE(counts.ok());
  EXPECT_THAT(counts->runs_by_state,
              ElementsAre(std::pair(RunState::kQueued, 1), std::pair(RunState::kRunning, 1),
                          std::pair(RunState::kCompleted, 0), std::pair(RunState::kFailed, 0),
                          std::pair(RunState::kCancelled, 0)));
  EXPECT_EQ(counts->free_learner_leases, 1);
  EXPECT_EQ(counts->free_slot_leases, 2);
}

EvaluationRequest Evaluation(int64_t policy_version, int contexts = 2) {
  return {.policy_version = policy_version,
          .step = 256 * policy_version,
          .contexts = contexts,
          .episodes = 3,
          .weights = std::string("w\0v", 3) + std::to_string(policy_version)};
}

std::optional<EvaluationGrant> AcquireJobs(Store& store, int max_jobs, int actors,
                                           absl::Time now = kStart, std::string numerics = "N",
                                           bool grid_cells = true) {
  absl::StatusOr<std::optional<EvaluationGrant>> grant =
      store.evaluations().AcquireEvaluationJobs("A", numerics, max_jobs, actors, grid_cells, now);
  EXPECT_TRUE(grant.ok()) << grant.status();
  return grant.ok() ? *grant : std::nullopt;
}

// One job, as its only key; nullopt if none was granted.
std::optional<EvaluationJobKey> AcquireJob(Store& store, absl::Time now = kStart,
                                           std::string numerics = "N") {
  std::optional<EvaluationGrant> grant = AcquireJobs(store, 1, 1, now, std::move(numerics));
  if (!grant.has_value()) return std::nullopt;
  EXPECT_EQ(grant->jobs.size(), 1u);
  return grant->jobs.front();
}

absl::StatusOr<bool> Report(Store& store, const EvaluationJobKey& job, ContextReturns result) {
  const JobResult delivered{.job = job, .result = std::move(result)};
  absl::StatusOr<std::vector<bool>> duplicate =
      store.evaluations().ReportEvaluationJobs({&delivered, 1});
  if (!duplicate.ok()) return duplicate.status();
  EXPECT_EQ(duplicate->size(), 1u);
  return duplicate->front();
}

TEST_F(RunStoreTest, AnEvaluationIsOneJobPerContextForActorsAndIsCompleteOnceAllAreIn) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(store->evaluations().SubmitEvaluation(learner, Evaluation(1), kStart).ok());
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 2);

  std::optional<EvaluationGrant> grant = AcquireJobs(*store, 1, 1);
  std::optional<EvaluationJobKey> second = AcquireJob(*store);
  ASSERT_TRUE(grant.has_value() && second.has_value());
  EXPECT_FALSE(AcquireJob(*store).has_value());
  const EvaluationJobKey first = grant->jobs.front();
  EXPECT_EQ(first.context, 0);
  EXPECT_EQ(second->context, 1);
  EXPECT_EQ(grant->weights, std::string("w\0v1", 4));  // bytes, NULs included
  EXPECT_EQ(grant->episodes, 3);
  EXPECT_EQ(grant->config, "env: cartpole\n");

  ASSERT_TRUE(Report(*store, *second, {{4.0, 5.0, 6.5}, 0.25}).ok());
  absl::StatusOr<EvaluationProgress> partial = store->evaluations().GetEvaluation("run-1", 1);
  ASSERT_TRUE(partial.ok());
  EXPECT_EQ(partial->done, 1);
  EXPECT_TRUE(partial->results.empty());

  ASSERT_TRUE(Report(*store, first, {{1.0, 2.0, 1.0 / 3.0}, 0.5}).ok());
  // A retry is acknowledged as one and changes nothing.
  EXPECT_EQ(Report(*store, first, {{9.0, 9.0, 9.0}, 0}).value_or(false), true);
  absl::StatusOr<EvaluationProgress> done = store->evaluations().GetEvaluation("run-1", 1);
  ASSERT_TRUE(done.ok());
  ASSERT_EQ(done->results.size(), 2u);
  EXPECT_THAT(done->results[0].returns, ElementsAre(1.0, 2.0, 1.0 / 3.0));  // exact doubles
  EXPECT_EQ(done->results[0].seconds, 0.5);
  EXPECT_THAT(done->results[1].returns, ElementsAre(4.0, 5.0, 6.5));
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 0);
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", 2).status().code(),
            absl::StatusCode::kNotFound);
}

// Issue 14 (found by tests/fuzz/run_store_fuzzer): an evaluation's job or returns numbered at or
// past its count of contexts in a damaged file were written past the end of the results (heap
// overflow); they are DATA_LOSS naming the file.
TEST_F(RunStoreTest, AnEvaluationContextOutsideItsCountIsDataLoss) {
  {
    std::unique_ptr<Store> store = Open();
    const LeaseKey learner = SubmitAndAcquire(*store).key;
    ASSERT_TRUE(store->evaluations().SubmitEvaluation(learner, Evaluation(1), kStart).ok());
    std::optional<EvaluationGrant> grant = AcquireJobs(*store, 2, 1);
    ASSERT_TRUE(grant.has_value() && grant->jobs.size() == 2u);
    ASSERT_TRUE(Report(*store, grant->jobs[0], {{1.0, 2.0, 3.0}, 0.5}).ok());
    ASSERT_TRUE(Report(*store, grant->jobs[1], {{4.0, 5.0, 6.0}, 0.5}).ok());
  }
  // Each damage on top of the ones before, and found before them.
  for (const auto& [sql, found] : std::vector<std::pair<std::string, std::string>>{
           {"UPDATE evaluation_returns SET context = 2 WHERE context = 1", "returns of context 2"},
           {"UPDATE evaluation_jobs SET context = 9 WHERE context = 1", "a job of context 9"},
           {"UPDATE evaluations SET contexts = 0", "contexts: 0"}}) {
    {
      SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE);
      db.exec("PRAGMA ignore_check_constraints = ON");
      db.exec(sql);
    }
    std::unique_ptr<Store> store = Open();
    const absl::Status status = store->evaluations().GetEvaluation("run-1", 1).status();
    EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss) << sql << ": " << status;
    EXPECT_THAT(status.message(), HasSubstr("coordinator.db is corrupt: the evaluation of policy "
                                            "version 1 of run-1 has " + found));
  }
}

TEST_F(RunStoreTest, ARunOfAnUnknownStateIsDataLossNotAFailedRun) {
  SubmitAndAcquire(*Open());
  {
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE);
    db.exec("PRAGMA ignore_check_constraints = ON");
    db.exec("UPDATE runs SET state = 'teleported'");
  }
  std::unique_ptr<Store> store = Open();
  const absl::Status status = store->runs().GetRun("run-1").status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss) << status;
  EXPECT_THAT(status.message(),
              HasSubstr("coordinator.db is corrupt: run-1 has an unknown state 'teleported'"));
  EXPECT_EQ(store->runs().ListRuns().status().code(), absl::StatusCode::kDataLoss);
}

TEST_F(RunStoreTest, AnActorTakesItsShareOfAnEvaluationsFreeJobsInOneGrant) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/5), kStart).ok());
  auto contexts = [](const std::optional<EvaluationGrant>& grant) {
    std::vector<int> taken;
    if (grant.has_value()) {
      for (const EvaluationJobKey& job : grant->jobs) taken.push_back(job.context);
    }
    return taken;
  };
  // Two actors share five free jobs: three (rounded up), then one of the two left.
  EXPECT_THAT(contexts(AcquireJobs(*store, /*max_jobs=*/8, /*actors=*/2)), ElementsAre(0, 1, 2));
  EXPECT_THAT(contexts(AcquireJobs(*store, /*max_jobs=*/8, /*actors=*/2)), ElementsAre(3));
  // One actor may take all that is left, but no more than it asks for.
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(2, /*contexts=*/3), kStart).ok());
  EXPECT_THAT(contexts(AcquireJobs(*store, /*max_jobs=*/8, /*actors=*/1)), ElementsAre(4));
  EXPECT_THAT(contexts(AcquireJobs(*store, /*max_jobs=*/2, /*actors=*/1)), ElementsAre(0, 1));
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 1);
}

TEST_F(RunStoreTest, AReportOfSeveralJobsIsStoredWholeOrNotAtAll) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/2), kStart).ok());
  std::optional<EvaluationGrant> grant = AcquireJobs(*store, 2, 1);
  ASSERT_TRUE(grant.has_value());
  ASSERT_EQ(grant->jobs.size(), 2u);
  std::vector<JobResult> results = {{grant->jobs[0], {{1, 2, 3}, 0}},
                                    {grant->jobs[1], {{4, 5}, 0}}};
  EXPECT_THAT(store->evaluations().ReportEvaluationJobs(results).status().message(),
              HasSubstr("context 1 of policy version 1 of run-1 has 3 episodes"));
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", 1)->done,
            0);  // the good one was not kept either

  results[1].result.returns.push_back(6);
  absl::StatusOr<std::vector<bool>> duplicate = store->evaluations().ReportEvaluationJobs(results);
  ASSERT_TRUE(duplicate.ok()) << duplicate.status();
  EXPECT_THAT(*duplicate, ElementsAre(false, false));
  EXPECT_THAT(*store->evaluations().ReportEvaluationJobs(results), ElementsAre(true, true));
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", 1)->done, 2);
}

TEST_F(RunStoreTest, SubmittingAnEvaluationAgainIsIdempotentAndNeedsTheLearnerLease) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(store->evaluations().SubmitEvaluation(learner, Evaluation(1), kStart).ok());
  ASSERT_TRUE(store->evaluations().SubmitEvaluation(learner, Evaluation(1), kStart).ok());
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 2);
  EXPECT_THAT(store->evaluations()
                  .SubmitEvaluation(learner, Evaluation(1, /*contexts=*/3), kStart)
                  .message(),
              HasSubstr("was submitted for evaluation with 2 contexts"));
  EXPECT_EQ(
      store->evaluations().SubmitEvaluation(learner, Evaluation(2, /*contexts=*/0), kStart).code(),
      absl::StatusCode::kInvalidArgument);
  LeaseKey stale = learner;
  stale.epoch = learner.epoch - 1;
  EXPECT_EQ(store->evaluations().SubmitEvaluation(stale, Evaluation(2), kStart).code(),
            absl::StatusCode::kFailedPrecondition);
}

TEST_F(RunStoreTest, ALapsedJobGoesBackToTheQueueAndWhicheverHolderDeliversFirstIsKept) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
  std::optional<EvaluationJobKey> old = AcquireJob(*store);
  ASSERT_TRUE(old.has_value());
  EXPECT_FALSE(AcquireJob(*store, kStart + kLease / 2).has_value());

  // The learner renews its own lease; the job outlasts its holder's.
  const absl::Time later = kStart + kLease + absl::Seconds(1);
  ASSERT_TRUE(store->runs().RenewLease(learner, kStart + kLease / 2).ok());
  std::optional<EvaluationJobKey> again = AcquireJob(*store, later);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->epoch, old->epoch + 1);

  // An epoch the job was never granted at is refused.
  EvaluationJobKey forged = *again;
  forged.epoch = again->epoch + 1;
  const absl::StatusOr<bool> refused = Report(*store, forged, {{1, 2, 3}, 0});
  EXPECT_EQ(refused.status().code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(refused.status().message(), HasSubstr("never granted at epoch 3"));
  forged.epoch = 0;
  EXPECT_EQ(Report(*store, forged, {{1, 2, 3}, 0}).status().code(),
            absl::StatusCode::kFailedPrecondition);

  // The old holder finishes first: its result is the job's, and the new holder's a duplicate.
  EXPECT_EQ(Report(*store, *old, {{1, 2, 3}, 0}).value_or(true), false);
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", 1)->done, 1);
  EXPECT_EQ(Report(*store, *again, {{1, 2, 3}, 0}).value_or(false), true);
}

TEST_F(RunStoreTest, ABadResultIsRefusedAndTheJobStaysOpen) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
  std::optional<EvaluationJobKey> job = AcquireJob(*store);
  ASSERT_TRUE(job.has_value());
  EXPECT_THAT(Report(*store, *job, {{1, 2}, 0}).status().message(),
              HasSubstr("has 3 episodes; 2 returns were delivered"));
  EXPECT_THAT(Report(*store, *job, {{1, std::nan(""), 3}, 0}).status().message(),
              HasSubstr("episode 1"));
  EvaluationJobKey unknown = *job;
  unknown.context = 5;
  EXPECT_EQ(Report(*store, unknown, {{1, 2, 3}, 0}).status().code(),
            absl::StatusCode::kNotFound);
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", 1)->done, 0);
  EXPECT_EQ(Report(*store, *job, {{1, 2, 3}, 0}).value_or(true), false);
}

TEST_F(RunStoreTest, JobsGoOnlyToActorsOfTheRunsNumericsAndOnlyWhileItRuns) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(store->runs().AcquireSlot("A", "M", {}, kStart).ok());  // pins the actors' numerics
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
  EXPECT_FALSE(AcquireJob(*store, kStart, "N").has_value());
  ASSERT_TRUE(store->runs().CancelRun("run-1", kStart).ok());
  EXPECT_FALSE(AcquireJob(*store, kStart, "M").has_value());
}

TEST_F(RunStoreTest, EvaluationsSurviveAReopen) {
  {
    std::unique_ptr<Store> store = Open();
    const LeaseKey learner = SubmitAndAcquire(*store).key;
    ASSERT_TRUE(
        store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
    std::optional<EvaluationJobKey> job = AcquireJob(*store);
    ASSERT_TRUE(job.has_value());
    ASSERT_TRUE(Report(*store, *job, {{1, 2, 3}, 0}).ok());
  }
  std::unique_ptr<Store> store = Open(kStart + absl::Seconds(60));
  absl::StatusOr<EvaluationProgress> evaluation = store->evaluations().GetEvaluation("run-1", 1);
  ASSERT_TRUE(evaluation.ok());
  ASSERT_EQ(evaluation->results.size(), 1u);
  EXPECT_THAT(evaluation->results[0].returns, ElementsAre(1, 2, 3));
}

TEST_F(RunStoreTest, AVersionOneDatabaseIsMigrated) {
  {
    // What DCS wrote before evaluations and sweeps were stored: a run leased to a learner.
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    ASSERT_TRUE(MigrateSchema(db, 1).ok());
    db.exec("INSERT INTO runs (request_id, config, seed, env, n_envs, total_timesteps, state, "
            "created_at, updated_at) VALUES ('request-1', 'env: cartpole', 7, 'cartpole', 2, "
            "1000, 'running', 0, 0);"
            "INSERT INTO leases (run, slot, epoch, holder, deadline) VALUES "
            "(1, -1, 1, 'L', 9000000000000000), (1, 0, 0, '', 0), (1, 1, 0, '', 0)");
  }
  std::unique_ptr<Store> store = Open();
  ASSERT_NE(store, nullptr);
  EXPECT_EQ(store->runs().GetRun("run-1")->state, RunState::kRunning);
  const LeaseKey learner{.run_id = "run-1", .slot = kLearnerSlot, .epoch = 1};
  EXPECT_TRUE(store->evaluations().SubmitEvaluation(learner, Evaluation(1), kStart).ok());
  SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA user_version").getInt(), CurrentSchemaVersion());
}

GridEvaluationRequest Grid(std::string request_id, int cells = 3,
                           std::string run_id = "run-1") {
  return {.request_id = std::move(request_id),
          .run_id = std::move(run_id),
          .cells = cells,
          .episodes = 2,
          .grid = std::string("g\0", 2) + std::to_string(cells),
          .weights = std::string("w\0g", 3)};
}

std::vector<int> ContextsOf(const std::optional<EvaluationGrant>& grant) {
  std::vector<int> taken;
  if (grant.has_value()) {
    for (const EvaluationJobKey& job : grant->jobs) taken.push_back(job.context);
  }
  return taken;
}

TEST_F(RunStoreTest, AGridEvaluationOfAnEndedRunIsOneJobPerCellWithResultsInCellOrder) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(
      store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
  ASSERT_TRUE(store->runs().FinishRun(learner, RunState::kCompleted, "", kStart).ok());

  absl::StatusOr<int64_t> key = store->evaluations().SubmitGridEvaluation(Grid("grid-a"), kStart);
  ASSERT_TRUE(key.ok()) << key.status();
  EXPECT_EQ(*key, -1);
  // A retry gets the same key and makes no jobs; another request gets the next key.
  EXPECT_EQ(store->evaluations().SubmitGridEvaluation(Grid("grid-a"), kStart).value_or(0), -1);
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 3);
  EXPECT_EQ(store->evaluations().SubmitGridEvaluation(Grid("grid-b", 1), kStart).value_or(0), -2);

  // Only an actor that evaluates grid cells gets them; the ended run's own evaluation is not
  // open any more.
  EXPECT_FALSE(AcquireJobs(*store, 8, 1, kStart, "N", /*grid_cells=*/false).has_value());
  std::optional<EvaluationGrant> grant = AcquireJobs(*store, 8, 1);
  ASSERT_TRUE(grant.has_value());
  ASSERT_THAT(ContextsOf(grant), ElementsAre(0, 1, 2));
  EXPECT_EQ(grant->jobs[0].policy_version, -1);
  EXPECT_EQ(grant->grid, std::string("g\0", 2) + "3");  // bytes, NULs included
  EXPECT_EQ(grant->weights, std::string("w\0g", 3));
  EXPECT_EQ(grant->episodes, 2);
  EXPECT_EQ(grant->config, "env: cartpole\n");

  // Delivered out of order, read in cell order.
  const std::vector<JobResult> results = {{grant->jobs[2], {{5, 6}, 0.5}},
                                          {grant->jobs[0], {{1, 2}, 0.5}}};
  ASSERT_TRUE(store->evaluations().ReportEvaluationJobs(results).ok());
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", -1)->done, 2);
  ASSERT_TRUE(Report(*store, grant->jobs[1], {{3, 4}, 0.5}).ok());
  absl::StatusOr<EvaluationProgress> done = store->evaluations().GetEvaluation("run-1", -1);
  ASSERT_TRUE(done.ok()) << done.status();
  ASSERT_EQ(done->contexts, 3);
  ASSERT_EQ(done->results.size(), 3u);
  EXPECT_THAT(done->results[0].returns, ElementsAre(1, 2));
  EXPECT_THAT(done->results[1].returns, ElementsAre(3, 4));
  EXPECT_THAT(done->results[2].returns, ElementsAre(5, 6));
  // Its policy is dropped; its results stay.
  SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("SELECT length(weights) FROM evaluations WHERE policy_version = -1")
                .getInt(),
            0);
  EXPECT_EQ(db.execAndGet("SELECT length(weights) FROM evaluations WHERE policy_version = -2")
                .getInt(),
            3);
}

TEST_F(RunStoreTest, AGridEvaluationNeedsAKnownRunAndAWholeRequest) {
  std::unique_ptr<Store> store = Open();
  SubmitAndAcquire(*store);
  EXPECT_EQ(
      store->evaluations().SubmitGridEvaluation(Grid("grid-a", 3, "run-9"), kStart).status().code(),
      absl::StatusCode::kNotFound);
  ASSERT_TRUE(store->runs().SubmitRun(Submission("request-2"), kStart).ok());
  ASSERT_TRUE(store->evaluations().SubmitGridEvaluation(Grid("grid-a"), kStart).ok());
  EXPECT_THAT(store->evaluations()
                  .SubmitGridEvaluation(Grid("grid-a", 3, "run-2"), kStart)
                  .status()
                  .message(),
              HasSubstr("request id grid-a made a grid evaluation of run-1, not of run-2"));
  for (GridEvaluationRequest bad : {Grid(""), Grid("grid-b", 0)}) {
    EXPECT_EQ(store->evaluations().SubmitGridEvaluation(bad, kStart).status().code(),
              absl::StatusCode::kInvalidArgument);
  }
  GridEvaluationRequest no_weights = Grid("grid-c");
  no_weights.weights.clear();
  EXPECT_EQ(store->evaluations().SubmitGridEvaluation(no_weights, kStart).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(store->Counts()->free_evaluation_jobs, 3);
}

TEST_F(RunStoreTest, ARunsOwnEvaluationGoesBeforeGridsAndNegativeVersionsAreTheGrids) {
  std::unique_ptr<Store> store = Open();
  const LeaseKey learner = SubmitAndAcquire(*store).key;
  ASSERT_TRUE(store->evaluations().SubmitGridEvaluation(Grid("grid-a", 4), kStart).ok());
  ASSERT_TRUE(store->evaluations()
                  .SubmitEvaluation(learner, Evaluation(1, 2), kStart + absl::Seconds(1))
                  .ok());
  EXPECT_EQ(store->evaluations().SubmitEvaluation(learner, Evaluation(-1), kStart).code(),
            absl::StatusCode::kInvalidArgument);
  std::optional<EvaluationGrant> first = AcquireJobs(*store, 8, 1);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->jobs[0].policy_version, 1);
  EXPECT_TRUE(first->grid.empty());
  // An actor takes its share of a grid's cells as of an evaluation's contexts.
  std::optional<EvaluationGrant> cells = AcquireJobs(*store, 8, 2);
  ASSERT_TRUE(cells.has_value());
  EXPECT_EQ(cells->jobs[0].policy_version, -1);
  EXPECT_THAT(ContextsOf(cells), ElementsAre(0, 1));
  // The run ends: its grid's policy stays for the cells still to run.
  ASSERT_TRUE(store->runs().FinishRun(learner, RunState::kCompleted, "", kStart).ok());
  std::optional<EvaluationGrant> rest = AcquireJobs(*store, 8, 1);
  ASSERT_TRUE(rest.has_value());
  EXPECT_THAT(ContextsOf(rest), ElementsAre(2, 3));
  EXPECT_EQ(rest->weights, std::string("w\0g", 3));
}

TEST_F(RunStoreTest, ALapsedGridCellGoesToAnotherActor) {
  std::unique_ptr<Store> store = Open();
  SubmitAndAcquire(*store);
  ASSERT_TRUE(store->evaluations().SubmitGridEvaluation(Grid("grid-a", 1), kStart).ok());
  std::optional<EvaluationJobKey> old = AcquireJob(*store);
  ASSERT_TRUE(old.has_value());
  EXPECT_FALSE(AcquireJob(*store, kStart + kLease / 2).has_value());
  std::optional<EvaluationJobKey> again = AcquireJob(*store, kStart + kLease + absl::Seconds(1));
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->policy_version, -1);
  EXPECT_EQ(again->epoch, old->epoch + 1);
  EXPECT_EQ(Report(*store, *again, {{1, 2}, 0}).value_or(true), false);
  EXPECT_EQ(Report(*store, *old, {{1, 2}, 0}).value_or(false), true);
  EXPECT_EQ(store->evaluations().GetEvaluation("run-1", -1)->done, 1);
}

TEST_F(RunStoreTest, AVersionFiveDatabaseIsMigratedWithItsEvaluations) {
  {
    // What DCS wrote before grid evaluations: a run with an evaluation of its own, done.
    std::unique_ptr<Store> store = Open();
    const LeaseKey learner = SubmitAndAcquire(*store).key;
    ASSERT_TRUE(
        store->evaluations().SubmitEvaluation(learner, Evaluation(1, /*contexts=*/1), kStart).ok());
    std::optional<EvaluationJobKey> job = AcquireJob(*store);
    ASSERT_TRUE(job.has_value());
    ASSERT_TRUE(Report(*store, *job, {{1, 2, 3}, 0}).ok());
    ASSERT_TRUE(store->runs().FinishRun(learner, RunState::kCompleted, "", kStart).ok());
  }
  {
    SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READWRITE);
    // Without what versions 6 and 7 added.
    db.exec("DROP TABLE grid_evaluations; DROP INDEX runs_by_state;");
    for (const char* column :
         {"runs DROP COLUMN latest_evaluation_step", "runs DROP COLUMN latest_avg_combined",
          "runs DROP COLUMN latest_id_return", "runs DROP COLUMN latest_ood_low_return",
          "runs DROP COLUMN latest_ood_high_return", "runs DROP COLUMN best_evaluation_step",
          "runs DROP COLUMN best_avg_combined", "leases DROP COLUMN granted_at"}) {
      db.exec(std::string("ALTER TABLE ") + column);
    }
    db.exec("PRAGMA user_version = 5");
  }
  std::unique_ptr<Store> store = Open();
  ASSERT_NE(store, nullptr);
  absl::StatusOr<EvaluationProgress> kept = store->evaluations().GetEvaluation("run-1", 1);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_THAT(kept->results[0].returns, ElementsAre(1, 2, 3));
  EXPECT_EQ(store->evaluations().SubmitGridEvaluation(Grid("grid-a"), kStart).value_or(0), -1);
  EXPECT_TRUE(store->Counts().ok());  // the columns metrics read are there
  SQLite::Database db(Path("coordinator.db"), SQLite::OPEN_READONLY);
  EXPECT_EQ(db.execAndGet("PRAGMA user_version").getInt(), CurrentSchemaVersion());
}

TEST(RunStateTest, OnlyTheTableMovesARun) {
  EXPECT_TRUE(CheckTransition("run-1", RunState::kQueued, RunState::kRunning).ok());
  EXPECT_TRUE(CheckTransition("run-1", RunState::kRunning, RunState::kQueued).ok());
  const absl::Status illegal = CheckTransition("run-1", RunState::kCompleted, RunState::kRunning);
  EXPECT_EQ(illegal.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(illegal.message(), "run run-1 is completed and cannot become running");
  EXPECT_FALSE(CheckTransition("run-1", RunState::kQueued, RunState::kCompleted).ok());
  for (const auto& [state, name] : kRunStateNames) {
    EXPECT_EQ(IsTerminal(state), state == RunState::kCompleted || state == RunState::kFailed ||
                                     state == RunState::kCancelled)
        << name;
  }
}

}  // namespace
}  // namespace dcs::coordinator
