// Copyright 2026 The DCS Authors.
#include "learner/training_run.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "env/bipedal_walker.h"
#include "env/car_racing.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "run/evaluation_log.h"
#include "tests/learner/small_run.h"
#include "tests/testing/temp_dir.h"

namespace dcs::learner {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::vector<std::vector<double>> Returns(const run::RunState& state) {
  std::vector<std::vector<double>> returns;
  for (const actor::EvaluationResult& evaluation : state.evaluations) {
    for (const actor::ContextResult& context : evaluation.contexts) {
      returns.push_back(context.returns);
    }
  }
  return returns;
}

class TrainingRunTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }
};

TEST_F(TrainingRunTest, SameSpecAndSeedGiveTheSameRunBitForBit) {
  const run::RunSpec spec = Spec(kSmallRun);
  absl::StatusOr<TrainingResult> first = Train<env::CartPole>(spec, {});
  absl::StatusOr<TrainingResult> second = Train<env::CartPole>(spec, {});
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_TRUE(second.ok()) << second.status();
  EXPECT_TRUE(first->complete);
  EXPECT_EQ(first->parameters, second->parameters);
  EXPECT_EQ(Returns(first->state), Returns(second->state));
  EXPECT_EQ(first->state.recent_returns, second->state.recent_returns);

  run::RunSpec other_seed = spec;
  other_seed.seed = 12;
  absl::StatusOr<TrainingResult> third = Train<env::CartPole>(other_seed, {});
  ASSERT_TRUE(third.ok()) << third.status();
  EXPECT_NE(first->parameters, third->parameters);
}

TEST_F(TrainingRunTest, EvaluatesThePolicyThatCollectedEachEvaluationStep) {
  absl::StatusOr<TrainingResult> run = Train<env::CartPole>(Spec(kSmallRun), {});
  ASSERT_TRUE(run.ok()) << run.status();
  // Rollouts are 128 steps (64 x 2 slots). Step 256 is reached by rollout 2, collected after
  // one update; the stage boundary 400 by rollout 4 (steps 385-512), after three; step 1280 is
  // both the last evaluation step and the end, evaluated before and after the last update.
  std::vector<std::pair<int64_t, int64_t>> steps_and_updates;
  for (const actor::EvaluationResult& evaluation : run->state.evaluations) {
    steps_and_updates.emplace_back(evaluation.step, evaluation.updates);
    ASSERT_EQ(evaluation.contexts.size(), 2u);
    EXPECT_EQ(evaluation.contexts[0].returns.size(), 2u);
    EXPECT_DOUBLE_EQ(evaluation.avg_combined,
                     (evaluation.contexts[0].mean + evaluation.contexts[1].mean) / 2);
  }
  EXPECT_THAT(steps_and_updates,
              ElementsAre(std::pair{256, 1}, std::pair{400, 3}, std::pair{512, 3},
                          std::pair{768, 5}, std::pair{1024, 7}, std::pair{1280, 9},
                          std::pair{1280, 10}));
  EXPECT_EQ(run->state.rollouts, 10);
  EXPECT_EQ(run->state.timesteps, 1280);
  // Stage boundaries 400 and 512 share weights and episodes: the same results.
  EXPECT_EQ(Returns(run->state)[2], Returns(run->state)[4]);
}

TEST_F(TrainingRunTest, StoppedAndResumedRunEndsWithTheWeightsOfAnUninterruptedOne) {
  const run::RunSpec spec = Spec(kSmallRun);
  absl::StatusOr<TrainingResult> straight = Train<env::CartPole>(spec, {});
  ASSERT_TRUE(straight.ok()) << straight.status();

  const std::string dir = testing::MakeTempDir();
  TrainingOptions options{.out_dir = dir,
                          .on_update = [](const TrainingProgress& p) { return p.updates < 5; }};
  absl::StatusOr<TrainingResult> first_half = Train<env::CartPole>(spec, options);
  ASSERT_TRUE(first_half.ok()) << first_half.status();
  EXPECT_FALSE(first_half->complete);
  EXPECT_EQ(first_half->state.timesteps, 640);
  EXPECT_NE(first_half->parameters, straight->parameters);

  absl::StatusOr<TrainingResult> resumed =
      Train<env::CartPole>(spec, {.out_dir = dir, .resume = true});
  ASSERT_TRUE(resumed.ok()) << resumed.status();
  EXPECT_TRUE(resumed->complete);
  EXPECT_EQ(resumed->parameters, straight->parameters);
  EXPECT_EQ(Returns(resumed->state), Returns(straight->state));
  EXPECT_EQ(resumed->state.recent_returns, straight->state.recent_returns);
}

TEST_F(TrainingRunTest, CountsCoverageInTheLogAndAResumedRunCountsOnExactly) {
  const run::RunSpec spec = Spec(absl::StrCat(kSmallRun, "coverage: {window: 500}\n"));
  absl::StatusOr<TrainingResult> straight = Train<env::CartPole>(spec, {});
  ASSERT_TRUE(straight.ok()) << straight.status();
  v1::EvaluationLog log;
  run::AppendCoverage(straight->state.coverage, 500, straight->state.timesteps, log);
  ASSERT_EQ(log.coverage_size(), 1);
  const v1::ProjectionCoverage& coverage = log.coverage(0);
  EXPECT_EQ(coverage.projection(), "state");
  ASSERT_EQ(coverage.windows_size(), 3);  // steps 1-500, 501-1000, 1001-1280
  EXPECT_EQ(coverage.windows(2).end_step(), 1280);
  int64_t seen = 0;
  for (uint64_t word : straight->state.coverage[0].seen) seen += std::popcount(word);
  int64_t new_cells = 0;
  for (const v1::CoverageWindow& window : coverage.windows()) {
    EXPECT_GT(window.visited(), 0);
    EXPECT_LE(window.new_cells(), window.visited());
    new_cells += window.new_cells();
  }
  EXPECT_EQ(new_cells, seen);
  EXPECT_EQ(coverage.windows(0).new_cells(), coverage.windows(0).visited());

  const std::string dir = testing::MakeTempDir();
  TrainingOptions options{.out_dir = dir,
                          .on_update = [](const TrainingProgress& p) { return p.updates < 6; }};
  ASSERT_TRUE(Train<env::CartPole>(spec, options).ok());  // stops at step 768, in window 2
  absl::StatusOr<TrainingResult> resumed =
      Train<env::CartPole>(spec, {.out_dir = dir, .resume = true});
  ASSERT_TRUE(resumed.ok()) << resumed.status();
  absl::StatusOr<v1::EvaluationLog> written = run::ReadEvaluationLog(dir);
  ASSERT_TRUE(written.ok()) << written.status();
  EXPECT_EQ(written->coverage(0).SerializeAsString(), coverage.SerializeAsString());
}

TEST_F(TrainingRunTest, WritesTheEvaluationLogAsCsvAndJson) {
  const std::string dir = testing::MakeTempDir();
  absl::StatusOr<TrainingResult> run = Train<env::CartPole>(Spec(kSmallRun), {.out_dir = dir});
  ASSERT_TRUE(run.ok()) << run.status();

  absl::StatusOr<v1::EvaluationLog> read = run::ReadEvaluationLog(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  const v1::EvaluationLog& log = *read;
  ASSERT_EQ(log.evaluations_size(), 7);
  EXPECT_TRUE(log.complete());
  EXPECT_EQ(log.seed(), 11u);
  EXPECT_EQ(log.last(), run->state.evaluations.back().avg_combined);
  // Multi-stage: best-anytime is over the stage boundaries (400, 512) and the end only.
  double best = -std::numeric_limits<double>::infinity();
  for (int i : {1, 2, 6}) best = std::max(best, run->state.evaluations[i].avg_combined);
  EXPECT_EQ(log.best_anytime(), best);
  EXPECT_EQ(log.evaluations(0).contexts(1).split(), v1::SPLIT_OOD_HIGH);
  EXPECT_EQ(log.evaluations(0).contexts(1).value(), 1.0);

  absl::StatusOr<std::string> csv = ReadFile(dir + "/evaluations.csv");
  ASSERT_TRUE(csv.ok()) << csv.status();
  const std::vector<std::string> lines = absl::StrSplit(*csv, '\n', absl::SkipEmpty());
  ASSERT_EQ(lines.size(), 1u + 7 * 2);
  EXPECT_EQ(lines[0], "step,updates,split,value,episodes,mean,std,seconds");
  EXPECT_THAT(lines[2], ::testing::StartsWith("256,1,ood_high,1,2,"));
}

TEST_F(TrainingRunTest, ResumeRefusesAMissingCheckpointOrAnotherRun) {
  const run::RunSpec spec = Spec(kSmallRun);
  const std::string dir = testing::MakeTempDir();
  EXPECT_EQ(Train<env::CartPole>(spec, {.out_dir = dir, .resume = true}).status().code(),
            absl::StatusCode::kNotFound);

  TrainingOptions stop_early{.out_dir = dir,
                             .on_update = [](const TrainingProgress&) { return false; }};
  ASSERT_TRUE(Train<env::CartPole>(spec, stop_early).ok());
  run::RunSpec other_seed = spec;
  other_seed.seed = 12;
  EXPECT_EQ(Train<env::CartPole>(other_seed, {.out_dir = dir, .resume = true}).status().code(),
            absl::StatusCode::kFailedPrecondition);
  run::RunSpec other_slots = spec;
  other_slots.n_envs = 4;
  const absl::Status status =
      Train<env::CartPole>(other_slots, {.out_dir = dir, .resume = true}).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(status.message(), HasSubstr("n_envs 4"));
}

// CartPole whose observation turns NaN at its 100th step in the run.
class NanCartPole {
 public:
  static constexpr absl::string_view kName = "nan_cartpole";
  using Observation = float;
  using ActionElement = int32_t;
  static constexpr int kObservationSize = env::CartPole::kObservationSize;
  static constexpr int kActionSize = env::CartPole::kActionSize;
  static constexpr int kNumActions = env::CartPole::kNumActions;
  static constexpr int kMaxEpisodeSteps = env::CartPole::kMaxEpisodeSteps;
  static const env::ContextSpace& Features() { return env::CartPole::Features(); }
  static absl::Status ValidateContext(std::span<const double> values) {
    return env::CartPole::ValidateContext(values);
  }
  double GetFeature(int feature) const { return cartpole_.GetFeature(feature); }
  void SetFeature(int feature, double value) { cartpole_.SetFeature(feature, value); }
  void Reset(Random& random, std::span<float, kObservationSize> observation) {
    cartpole_.Reset(random, observation);
  }
  env::StepResult Step(std::span<const int32_t, kActionSize> action,
                       std::span<float, kObservationSize> observation) {
    const env::StepResult result = cartpole_.Step(action, observation);
    if (++steps_ == 100) observation[2] = std::nanf("");
    return result;
  }

 private:
  env::CartPole cartpole_;
  int steps_ = 0;
};

TEST_F(TrainingRunTest, NanObservationStopsTheRunNamingWhereAndKeepsTheCheckpoints) {
  run::RunSpec spec = Spec(kSmallRun);
  spec.n_envs = 1;
  spec.stages.clear();
  spec.eval_freq = 64;
  const std::string dir = testing::MakeTempDir();
  const absl::Status status = Train<NanCartPole>(spec, {.out_dir = dir}).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("environment steps 64 to 128"));
  EXPECT_THAT(status.message(), HasSubstr("not finite"));
  // The update after rollout 0 was checkpointed; nothing after it was.
  absl::StatusOr<run::Checkpoint> checkpoint = run::ReadLatestCheckpoint(dir);
  ASSERT_TRUE(checkpoint.ok()) << checkpoint.status();
  EXPECT_EQ(checkpoint->state.timesteps, 64);
}

TEST_F(TrainingRunTest, ReportsProgressAfterEveryUpdate) {
  std::vector<TrainingProgress> reports;
  absl::StatusOr<TrainingResult> run = Train<env::CartPole>(
      Spec(kSmallRun), {.on_update = [&](const TrainingProgress& progress) {
        reports.push_back(progress);
        return true;
      }});
  ASSERT_TRUE(run.ok()) << run.status();
  ASSERT_EQ(reports.size(), 10u);
  EXPECT_EQ(reports[0].timesteps, 128);
  EXPECT_EQ(reports[0].updates, 1);
  EXPECT_EQ(reports[0].evaluation, nullptr);
  EXPECT_EQ(reports[9].total_timesteps, 1280);
  EXPECT_GT(reports[9].steps_per_second, 0);
  EXPECT_GT(reports[9].recent_return, 0);
  EXPECT_EQ(reports[9].update.gradient_steps, 2 * (128 / 32));
}

TEST_F(TrainingRunTest, ContinuousControlTrainsAndEvaluatesBipedalWalker) {
  absl::StatusOr<TrainingResult> run = Train<env::BipedalWalker>(Spec(R"(
env: bipedal_walker
total_timesteps: 256
feature: COM_X
training_range: [-0.6, 0.6]
pool: {size: 3}
evaluation: {freq: 128, episodes: 1, contexts: {id: [0.0]}}
ppo: {n_steps: 128, batch_size: 64, n_epochs: 2}
)"),
                                                                {});
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->state.rollouts, 2);
  ASSERT_EQ(run->state.evaluations.size(), 3u);
  for (const actor::EvaluationResult& evaluation : run->state.evaluations) {
    EXPECT_TRUE(std::isfinite(evaluation.avg_combined));
  }
}

TEST_F(TrainingRunTest, CnnPolicyTrainsAFewUpdatesOnCarRacing) {
  const run::RunSpec spec = Spec(R"(
env: car_racing
total_timesteps: 64
feature: COM_Y
training_range: [-0.8, 0.8]
observe: live
evaluation: {freq: 1000, episodes: 1, contexts: {id: [0.0]}}
ppo: {n_steps: 32, batch_size: 16, n_epochs: 2}
)");
  absl::StatusOr<std::unique_ptr<PpoLearner>> untrained = PpoLearner::Create(
      run::PolicySpecFor<env::CarRacing>(1), spec.ppo, spec.n_envs, spec.seed);
  ASSERT_TRUE(untrained.ok()) << untrained.status();
  absl::StatusOr<TrainingResult> run = Train<env::CarRacing>(spec, {});
  ASSERT_TRUE(run.ok()) << run.status();
  EXPECT_EQ(run->state.rollouts, 2);
  EXPECT_NE(run->parameters, (*untrained)->Parameters());
  for (float parameter : run->parameters) ASSERT_TRUE(std::isfinite(parameter));
  ASSERT_EQ(run->state.evaluations.size(), 1u);
  EXPECT_TRUE(std::isfinite(run->state.evaluations[0].avg_combined));
}

}  // namespace
}  // namespace dcs::learner
