// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_COORDINATOR_STUDY_SWEEP_FIXTURE_H_
#define DCS_TESTS_COORDINATOR_STUDY_SWEEP_FIXTURE_H_

// Study sweeps on a real SQLite store, with learners played by the test: runs are leased, their
// evaluation logs written into their directories and finished. Shared by the tests of a sweep's
// step (coordinator/study_sweep.h) and of its driver (coordinator/study_sweep_driver.h).

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/time/time.h"
#include "coordinator/run_files.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/sweep_results.h"
#include "coordinator/sweep_submission.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {

inline const absl::Time kNow = absl::FromUnixSeconds(1'800'000'000);

// Two stages of 1000 steps; one categorical per stage, a sinusoid's period conditional on it.
inline constexpr char kSpec[] = R"(name: search
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

// A real SQLite store in a temporary directory, a study sweep submitted to it, and learners played
// by the test.
class StudySweepFixture : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    absl::StatusOr<std::unique_ptr<Store>> store = Store::Open(Path("coordinator.db"), {}, kNow);
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = *std::move(store);
    logs_ = std::make_unique<CompletedRunLogs>(Path("data"));
  }

  // Submits the study sweep of `spec_text`; spec_ is its spec, as read at submission.
  SweepRecord Submit(const std::string& spec_text) {
    absl::StatusOr<ExpandedSweep> expanded = ExpandSweep(spec_text, "search.yaml", "", "req");
    EXPECT_TRUE(expanded.ok()) << expanded.status();
    EXPECT_TRUE(expanded->study.has_value());
    absl::StatusOr<SweepRecord> sweep = store_->sweeps().SubmitSweep(expanded->submission, kNow);
    EXPECT_TRUE(sweep.ok()) << sweep.status();
    spec_ = *std::move(expanded->study);
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

}  // namespace dcs::coordinator

#endif  // DCS_TESTS_COORDINATOR_STUDY_SWEEP_FIXTURE_H_
