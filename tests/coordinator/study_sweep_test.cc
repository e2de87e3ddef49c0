// Copyright 2026 The DCS Authors.
//
// Study sweeps (coordinator/study_sweep.h) driven step by step on a real SQLite store, with
// learners played by the test: runs are leased, their evaluation logs written into their
// directories and finished, and the driver asks, queues, tells, prunes and retrains.

#include "coordinator/study_sweep.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "coordinator/run_files.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/sweep_submission.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

const absl::Time kNow = absl::FromUnixSeconds(1'800'000'000);

// Two stages of 1000 steps; one categorical per stage, a sinusoid's period conditional on it.
constexpr char kSpec[] = R"(name: search
seeds: 2
observe: [live]
env: cartpole
total_timesteps: 2000
evaluation: {freq: 100000, episodes: 2, contexts: {id: [0.5]}}
ppo: {n_steps: 250, batch_size: 50}
conditions:
  - name: base
    stages:
      - {steps: 1000, schedule: {family: constant}}
      - {steps: 1000, schedule: {family: constant}}
study:
  trials: 5
  parallel: 2
  sampler: random
  seed: 7
  retrain: {top_k: 2, seeds: 3}
  space:
    parameters:
      - {name: "stages[0].schedule.family", type: categorical, choices: [constant, sinusoidal]}
      - {name: "stages[0].schedule.amplitude_frac", type: float, low: 0.1, high: 1,
         when: {"stages[0].schedule.family": sinusoidal}}
      - {name: "stages[1].schedule.family", type: categorical, choices: [constant, sinusoidal]}
)";

class StudySweepTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    absl::StatusOr<std::unique_ptr<Store>> store = Store::Open(Path("coordinator.db"), {}, kNow);
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = *std::move(store);
    logs_ = std::make_unique<CompletedRunLogs>(Path("data"));
  }

  SweepRecord Submit(const std::string& spec_text) {
    absl::StatusOr<ExpandedSweep> expanded = ExpandSweep(spec_text, "search.yaml", "", "req");
    EXPECT_TRUE(expanded.ok()) << expanded.status();
    absl::StatusOr<SweepRecord> sweep = store_->sweeps().SubmitSweep(expanded->submission, kNow);
    EXPECT_TRUE(sweep.ok()) << sweep.status();
    absl::StatusOr<StudySweepSpec> spec = ParseStudySweepYaml(spec_text, "search.yaml");
    EXPECT_TRUE(spec.ok()) << spec.status();
    spec_ = *std::move(spec);
    return *sweep;
  }

  StudySweepStep Advance(const std::string& sweep_id) {
    absl::StatusOr<SweepRecord> sweep = store_->sweeps().GetSweep(sweep_id);
    EXPECT_TRUE(sweep.ok()) << sweep.status();
    absl::StatusOr<StudySweepStep> step =
        AdvanceStudySweep(*store_, Path("data"), *logs_, *sweep, spec_, kNow);
    EXPECT_TRUE(step.ok()) << step.status();
    return step.value_or(StudySweepStep{});
  }

  // A learner takes a queued run.
  LeaseKey Lease() {
    absl::StatusOr<std::optional<LearnerLease>> lease =
        store_->runs().AcquireRun("learner", "127.0.0.1:1", "numerics", kNow);
    EXPECT_TRUE(lease.ok() && lease->has_value()) << lease.status();
    return lease.ok() && lease->has_value() ? (*lease)->key : LeaseKey{};
  }

  // The run's learner writes its log, an evaluation at each step of `scores`, and reports its
  // progress; with `finish`, the run completes.
  void Evaluate(const LeaseKey& key, const std::map<int64_t, double>& scores, bool finish) {
    v1::EvaluationLog log;
    log.set_complete(finish);
    double best = -1e9;
    for (const auto& [step, score] : scores) {
      v1::Evaluation* evaluation = log.add_evaluations();
      evaluation->set_step(step);
      evaluation->set_avg_combined(score);
      best = std::max(best, score);
      log.set_last(score);
    }
    log.set_best_anytime(best);
    EXPECT_TRUE(run::WriteEvaluationLog(RunDirectory(Path("data"), key.run_id), log).ok());
    const RunProgress progress{.timesteps = scores.rbegin()->first,
                               .avg_combined = log.last(),
                               .evaluation_step = scores.rbegin()->first};
    EXPECT_TRUE(store_->runs().ReportProgress(key, progress, kNow).ok());
    if (finish) {
      EXPECT_TRUE(store_->runs().FinishRun(key, RunState::kCompleted, "", kNow).ok());
    }
  }

  // A run leased, evaluated and (with `finish`) completed.
  LeaseKey Train(const std::map<int64_t, double>& scores, bool finish) {
    const LeaseKey key = Lease();
    Evaluate(key, scores, finish);
    return key;
  }

  std::vector<StudyTrial> Trials(const SweepRecord& sweep) {
    absl::StatusOr<std::vector<StudyTrial>> trials =
        store_->studies().ListStudyTrials(sweep.study_id);
    EXPECT_TRUE(trials.ok()) << trials.status();
    return trials.value_or(std::vector<StudyTrial>{});
  }

  std::unique_ptr<Store> store_;
  std::unique_ptr<CompletedRunLogs> logs_;
  StudySweepSpec spec_;
};

TEST_F(StudySweepTest, AsksTrainsTellsAndRetrainsTheBest) {
  const SweepRecord submitted = Submit(kSpec);
  EXPECT_TRUE(submitted.open);
  EXPECT_EQ(submitted.study_id, "study-1");
  EXPECT_EQ(submitted.state, SweepState::kQueued);

  // Two trials in parallel, each with both seeds; a second step asks nothing more.
  EXPECT_EQ(Advance(submitted.id).asked, 2);
  EXPECT_EQ(Advance(submitted.id).asked, 0);
  absl::StatusOr<SweepRecord> sweep = store_->sweeps().GetSweep(submitted.id);
  ASSERT_TRUE(sweep.ok());
  ASSERT_EQ(sweep->trials.size(), 2u);
  EXPECT_EQ(sweep->trials[0].condition, "T000");
  EXPECT_EQ(sweep->trials[1].study_trial, 1);
  EXPECT_EQ(sweep->trials[0].family, "multi_stage");
  EXPECT_EQ(sweep->trials[0].observe, "live");
  absl::StatusOr<std::vector<RunRecord>> runs = store_->sweeps().ListSweepRuns(submitted.id);
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 4u);
  EXPECT_EQ((*runs)[0].submission.seed, 0u);
  EXPECT_EQ((*runs)[1].submission.seed, 1u);
  EXPECT_EQ((*runs)[0].trial, 0);
  // Each run's config is its trial's: the sampled family where the space names it.
  const std::vector<StudyTrial> asked = Trials(*sweep);
  const std::string& family =
      run::ChoiceOf(std::get<run::CategoricalDistribution>(spec_.space.parameters[0].distribution),
                    asked[0].values.at("stages[0].schedule.family"));
  EXPECT_THAT((*runs)[0].submission.config, HasSubstr(absl::StrCat("family: ", family)));

  // Trial 0's seeds score best-anytime 10 and 30 (the objective: their mean, 20).
  Train({{1000, 10}, {2000, 5}}, true);
  Train({{1000, 20}, {2000, 30}}, true);
  StudySweepStep step = Advance(submitted.id);
  EXPECT_EQ(step.told, 1);
  EXPECT_EQ(step.asked, 1);  // its place goes to trial 2
  EXPECT_EQ(Trials(*sweep)[0].state, TrialState::kComplete);
  EXPECT_DOUBLE_EQ(Trials(*sweep)[0].value, 20);

  // The other trials, with objectives 50, 40, 10, 60 in the order they finish.
  for (double score : {50.0, 40.0, 10.0, 60.0}) {
    Train({{2000, score}}, true);
    Train({{2000, score}}, true);
    Advance(submitted.id);
  }
  std::vector<StudyTrial> trials = Trials(*sweep);
  ASSERT_EQ(trials.size(), 5u);
  std::vector<double> values;
  for (const StudyTrial& trial : trials) values.push_back(trial.value);
  EXPECT_THAT(values, ElementsAre(20, 50, 40, 10, 60));

  // The search ended: the two best (trials 4 and 1) retrain with 3 new seeds, and the sweep
  // closes.
  sweep = store_->sweeps().GetSweep(submitted.id);
  ASSERT_TRUE(sweep.ok());
  EXPECT_FALSE(sweep->open);
  ASSERT_EQ(sweep->trials.size(), 7u);
  EXPECT_EQ(sweep->trials[5].condition, "T004 retrain");
  EXPECT_TRUE(sweep->trials[5].retrain);
  EXPECT_EQ(sweep->trials[6].condition, "T001 retrain");
  runs = store_->sweeps().ListSweepRuns(submitted.id);
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 16u);
  std::vector<uint64_t> retrain_seeds;
  for (const RunRecord& run : *runs) {
    if (run.trial == 5) retrain_seeds.push_back(run.submission.seed);
  }
  EXPECT_THAT(retrain_seeds, ElementsAre(2, 3, 4));  // after the search's seeds 0 and 1
  EXPECT_EQ(sweep->state, SweepState::kRunning);
}

TEST_F(StudySweepTest, AStepCutShortIsFinishedByTheNext) {
  const SweepRecord sweep = Submit(kSpec);
  // A step asked for trial 0 and stopped before queueing its runs.
  ASSERT_TRUE(store_->studies().AskTrial(sweep.study_id, "req/ask/0", kNow).ok());
  const StudySweepStep step = Advance(sweep.id);
  EXPECT_EQ(step.asked, 1);  // trial 1 only: trial 0 is queued, not asked again
  std::vector<StudyTrial> trials = Trials(sweep);
  EXPECT_EQ(trials.size(), 2u);
  absl::StatusOr<SweepRecord> stepped = store_->sweeps().GetSweep(sweep.id);
  ASSERT_TRUE(stepped.ok());
  ASSERT_EQ(stepped->trials.size(), 2u);
  EXPECT_EQ(stepped->trials[0].study_trial, 0);

  // Queueing a trial again adds nothing.
  absl::StatusOr<std::vector<RunRecord>> before = store_->sweeps().ListSweepRuns(sweep.id);
  ASSERT_TRUE(before.ok());
  absl::StatusOr<std::vector<RunRecord>> again = store_->sweeps().AddSweepTrial(
      sweep.id, stepped->trials[0], {before->front().submission}, kNow);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(again->size(), 2u);
  absl::StatusOr<std::vector<RunRecord>> after = store_->sweeps().ListSweepRuns(sweep.id);
  ASSERT_TRUE(after.ok());
  EXPECT_EQ(after->size(), before->size());
}

TEST_F(StudySweepTest, AFailedRunFailsItsTrial) {
  const SweepRecord sweep = Submit(kSpec);
  Advance(sweep.id);
  Train({{2000, 10}}, true);
  ASSERT_TRUE(store_->runs().FinishRun(Lease(), RunState::kFailed, "NaN loss", kNow).ok());
  EXPECT_EQ(Advance(sweep.id).told, 1);
  EXPECT_EQ(Trials(sweep)[0].state, TrialState::kFailed);
}

TEST_F(StudySweepTest, CancellingTheSweepFailsItsRunningTrialsAndClosesIt) {
  const SweepRecord sweep = Submit(kSpec);
  Advance(sweep.id);
  absl::StatusOr<SweepRecord> cancelled = store_->sweeps().CancelSweep(sweep.id, kNow);
  ASSERT_TRUE(cancelled.ok()) << cancelled.status();
  EXPECT_FALSE(cancelled->open);
  EXPECT_EQ(cancelled->state, SweepState::kCancelled);
  for (const StudyTrial& trial : Trials(sweep)) EXPECT_EQ(trial.state, TrialState::kFailed);
  absl::StatusOr<std::vector<SweepRecord>> open = store_->sweeps().ListOpenSweeps();
  ASSERT_TRUE(open.ok());
  EXPECT_TRUE(open->empty());
  EXPECT_EQ(store_->sweeps().RetrySweep(sweep.id, kNow).status().code(),
            absl::StatusCode::kFailedPrecondition);

  // A step that read the sweep before the cancel asks for a trial it cannot queue: it fails too,
  // the step asks no more, and no trial is left running.
  absl::StatusOr<StudySweepStep> late =
      AdvanceStudySweep(*store_, Path("data"), *logs_, sweep, spec_, kNow);
  ASSERT_TRUE(late.ok()) << late.status();
  EXPECT_EQ(late->asked, 1);
  for (const StudyTrial& trial : Trials(sweep)) EXPECT_EQ(trial.state, TrialState::kFailed);
}

TEST_F(StudySweepTest, TheMedianPrunerStopsATrialBehindAtAStageBoundary) {
  std::string spec = kSpec;
  spec.replace(spec.find("  retrain: {top_k: 2, seeds: 3}\n"),
               std::string("  retrain: {top_k: 2, seeds: 3}\n").size(),
               "  pruner: {kind: median, startup_trials: 1}\n");
  spec.replace(spec.find("parallel: 2"), std::string("parallel: 2").size(), "parallel: 1");
  const SweepRecord sweep = Submit(spec);
  Advance(sweep.id);
  // Trial 0's seeds both score 50 at the boundary, then complete between two steps: its
  // boundary is reported before it is told.
  Train({{1000, 50}, {2000, 50}}, true);
  Train({{1000, 50}, {2000, 50}}, true);
  StudySweepStep step = Advance(sweep.id);
  EXPECT_EQ(step.reported, 1);
  EXPECT_EQ(step.told, 1);
  // Trial 1's seeds are at 10 at the boundary, still training: worse than the median, pruned.
  Train({{1000, 10}}, false);
  Train({{1000, 10}}, false);
  step = Advance(sweep.id);
  EXPECT_EQ(step.reported, 1);
  EXPECT_EQ(step.told, 1);
  const std::vector<StudyTrial> trials = Trials(sweep);
  EXPECT_EQ(trials[1].state, TrialState::kPruned);
  EXPECT_THAT(trials[1].reported, ElementsAre(std::pair<const int64_t, double>(1000, 10)));
  absl::StatusOr<std::vector<RunRecord>> runs = store_->sweeps().ListSweepRuns(sweep.id);
  ASSERT_TRUE(runs.ok());
  EXPECT_EQ((*runs)[2].state, RunState::kCancelled);
  EXPECT_EQ((*runs)[3].state, RunState::kCancelled);
}

TEST(ObjectiveAtTest, BestAnytimeCountsBoundariesUpToTheStep) {
  v1::EvaluationLog a;
  for (auto [step, score] :
       std::vector<std::pair<int64_t, double>>{{500, 99}, {1000, 10}, {1500, 70}, {2000, 20}}) {
    v1::Evaluation* evaluation = a.add_evaluations();
    evaluation->set_step(step);
    evaluation->set_avg_combined(score);
  }
  v1::EvaluationLog b = a;
  b.mutable_evaluations(1)->set_avg_combined(30);
  // At 1000: the boundary's own (500 is no boundary); at 2000: the best of 1000 and 2000.
  EXPECT_EQ(ObjectiveAt(StudyObjective::kBestAnytime, {a, b}, {1000}, 1000), 20);
  EXPECT_EQ(ObjectiveAt(StudyObjective::kBestAnytime, {a, b}, {1000}, 2000), 25);
  EXPECT_EQ(ObjectiveAt(StudyObjective::kLastIqm, {a, b}, {1000}, 2000), 20);
  EXPECT_EQ(ObjectiveAt(StudyObjective::kBestAnytime, {a, b}, {1000}, 3000), std::nullopt);
}

}  // namespace
}  // namespace dcs::coordinator
