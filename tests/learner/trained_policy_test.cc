// Copyright 2026 The DCS Authors.
//
// A run's policy loaded from its directory (learner/trained_policy.h): the last checkpoint, a
// kept step, or the best on the run's protocol, whose recorded scores are what evaluating the
// policy again gives; a checkpoint read strictly, never replaced by an older one.

#include "learner/trained_policy.h"

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "run/run_directory.h"
#include "tests/learner/small_run.h"
#include "tests/testing/temp_dir.h"

namespace dcs::learner {
namespace {

using ::testing::HasSubstr;

class TrainedPolicyTest : public ::testing::Test {
 protected:
  // kSmallRun trained into a directory of its own, every checkpoint kept.
  static void SetUpTestSuite() {
    PinTorchThreads(1).IgnoreError();
    dir_ = new std::string(testing::MakeTempDir() + "/run");
    absl::StatusOr<run::RunRequest> request = run::RequestRun(kSmallRun, "small.yaml", *dir_, "");
    ASSERT_TRUE(request.ok()) << request.status();
    ASSERT_TRUE(run::CreateRunDirectory(*request).ok());
    absl::StatusOr<TrainingResult> result =
        Train<env::CartPole>(request->spec, {.out_dir = *dir_, .keep_checkpoints = 100});
    ASSERT_TRUE(result.ok()) << result.status();
    log_ = new v1::EvaluationLog(result->log);
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete log_;
  }

  // avg_combined of `trained`'s policy, evaluated now on its run's protocol.
  static double Evaluated(const TrainedPolicy& trained) {
    actor::PolicyNetwork policy = *actor::PolicyNetwork::Create(trained.learner->ActorWeights());
    absl::StatusOr<actor::EvaluationResult> result = actor::Evaluate<env::CartPole>(
        policy, trained.plan.slot, trained.plan.feature, trained.plan.evaluation_contexts,
        trained.run.spec.eval_episodes, trained.run.spec.seed);
    EXPECT_TRUE(result.ok()) << result.status();
    return result.ok() ? result->avg_combined : -1;
  }

  static std::string* dir_;
  static v1::EvaluationLog* log_;
};

std::string* TrainedPolicyTest::dir_ = nullptr;
v1::EvaluationLog* TrainedPolicyTest::log_ = nullptr;

TEST_F(TrainedPolicyTest, TheLastCheckpointIsTheRunsEnd) {
  absl::StatusOr<TrainedPolicy> last = LoadTrainedPolicy(*dir_, "last");
  ASSERT_TRUE(last.ok()) << last.status();
  EXPECT_EQ(last->step, 1280);
  EXPECT_EQ(last->learner->updates(), 10);
  // The run evaluated this policy at its end: evaluating it again gives the same score.
  ASSERT_GT(log_->evaluations_size(), 0);
  EXPECT_EQ(log_->evaluations(log_->evaluations_size() - 1).updates(), 10);
  EXPECT_EQ(Evaluated(*last), log_->last());
}

TEST_F(TrainedPolicyTest, TheBestIsTheKeptCheckpointThatScoresHighest) {
  absl::StatusOr<TrainedPolicy> best = LoadTrainedPolicy(*dir_, "best");
  ASSERT_TRUE(best.ok()) << best.status();
  double highest = -1;
  std::vector<std::string> names = *run::CheckpointNames(*dir_);
  ASSERT_GT(names.size(), 2u);
  for (const std::string& name : names) {
    absl::StatusOr<TrainedPolicy> kept = LoadTrainedPolicy(*dir_, name);
    ASSERT_TRUE(kept.ok()) << kept.status();
    highest = std::max(highest, Evaluated(*kept));
  }
  EXPECT_EQ(Evaluated(*best), highest);
}

TEST_F(TrainedPolicyTest, AStepMustBeAKeptCheckpoints) {
  const std::vector<std::string> names = *run::CheckpointNames(*dir_);
  absl::StatusOr<TrainedPolicy> kept = LoadTrainedPolicy(*dir_, names.front());
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_EQ(run::CheckpointName(kept->step), names.front());
  EXPECT_TRUE(absl::IsNotFound(LoadTrainedPolicy(*dir_, "7").status()));
  EXPECT_TRUE(absl::IsInvalidArgument(LoadTrainedPolicy(*dir_, "newest").status()));
  EXPECT_TRUE(absl::IsNotFound(LoadTrainedPolicy(*dir_ + "-missing", "last").status()));
}

TEST_F(TrainedPolicyTest, ACorruptLastCheckpointIsAnErrorNotAnOlderOne) {
  const std::string copy = testing::MakeTempDir() + "/run";
  std::filesystem::copy(*dir_, copy, std::filesystem::copy_options::recursive);
  const std::string learner = copy + "/checkpoints/" + run::CheckpointName(1280) + "/learner.bin";
  {
    std::fstream file(learner, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(64);
    file.put('\x55');
  }
  absl::StatusOr<TrainedPolicy> last = LoadTrainedPolicy(copy, "last");
  EXPECT_TRUE(absl::IsDataLoss(last.status())) << last.status();
  EXPECT_THAT(last.status().message(), HasSubstr(learner));
}

}  // namespace
}  // namespace dcs::learner
