// Copyright 2026 The DCS Authors.
#include "learner/ppo_learner.h"

#include <cmath>
#include <limits>
#include <thread>
#include <vector>

#include "actor/policy_network.h"
#include "common/random.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"

namespace dcs::learner {
namespace {

using ::testing::HasSubstr;

constexpr int kSteps = 256;

run::PolicySpec BanditSpec() {
  return {.observation_size = 4, .context_size = 1, .num_actions = 2, .action_size = 1};
}

run::PpoConfig SmallConfig() { return {.n_steps = kSteps, .batch_size = 64, .n_epochs = 4}; }

// A two-armed bandit as a rollout: random observations, actions sampled from the learner's
// current policy, reward 1 for action 1; episodes of 32 steps.
actor::Rollout BanditRollout(PpoLearner& learner, uint64_t seed) {
  actor::PolicyNetwork policy = *actor::PolicyNetwork::Create(learner.ActorWeights());
  Random random(seed);
  actor::Rollout rollout{.num_steps = kSteps, .num_envs = 1};
  for (int t = 0; t < kSteps; ++t) {
    std::vector<float> input(5);
    for (float& x : input) x = static_cast<float>(random.Uniform(-1, 1));
    float action = 0;
    policy.Act(1, input, /*images=*/{}, /*deterministic=*/false, {&random, 1}, {&action, 1});
    rollout.inputs.insert(rollout.inputs.end(), input.begin(), input.end());
    rollout.actions.push_back(action);
    rollout.rewards.push_back(action);
    rollout.episode_starts.push_back(t % 32 == 0);
  }
  rollout.last_inputs = std::vector<float>(5, 0.0f);
  rollout.last_dones = {1};
  return rollout;
}

std::unique_ptr<PpoLearner> NewLearner(uint64_t seed) {
  absl::StatusOr<std::unique_ptr<PpoLearner>> learner =
      PpoLearner::Create(BanditSpec(), SmallConfig(), 1, seed);
  EXPECT_TRUE(learner.ok()) << learner.status();
  return *std::move(learner);
}

class PpoLearnerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }
};

TEST_F(PpoLearnerTest, LearnsToPreferTheRewardedAction) {
  std::unique_ptr<PpoLearner> learner = NewLearner(1);
  for (int update = 0; update < 60; ++update) {
    absl::StatusOr<UpdateStats> stats = learner->Update(BanditRollout(*learner, update));
    ASSERT_TRUE(stats.ok()) << stats.status();
    EXPECT_EQ(stats->gradient_steps, 4 * kSteps / 64);
  }
  actor::PolicyNetwork policy = *actor::PolicyNetwork::Create(learner->ActorWeights());
  Random random(99);
  int rewarded = 0;
  for (int i = 0; i < 1000; ++i) {
    std::vector<float> input(5);
    for (float& x : input) x = static_cast<float>(random.Uniform(-1, 1));
    float action = 0;
    policy.Act(1, input, /*images=*/{}, false, {&random, 1}, {&action, 1});
    rewarded += action == 1;
  }
  EXPECT_GT(rewarded, 900);  // from about 500 before training
  EXPECT_EQ(learner->updates(), 60);
}

TEST_F(PpoLearnerTest, GradNormIsTheNormGradientClippingSees) {
  // One gradient step per update (one epoch of one minibatch), so the mean is that step's.
  run::PpoConfig config = {.n_steps = kSteps, .batch_size = kSteps, .n_epochs = 1};
  const auto update = [&](double max_grad_norm, const actor::Rollout& rollout,
                          std::vector<float>& parameters) {
    config.max_grad_norm = max_grad_norm;
    std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(BanditSpec(), config, 1, 3);
    absl::StatusOr<UpdateStats> stats = learner->Update(rollout);
    EXPECT_TRUE(stats.ok()) << stats.status();
    parameters = learner->Parameters();
    return stats.value_or(UpdateStats{});
  };
  const actor::Rollout rollout = BanditRollout(*NewLearner(3), 7);
  std::vector<float> unclipped;
  const double norm = update(1e9, rollout, unclipped).grad_norm;
  ASSERT_GT(norm, 0);
  // Clipping just above the norm leaves the step as it was; just below, it scales the
  // gradient (Adam's eps makes that show in the weights). Both report the norm before.
  std::vector<float> above;
  std::vector<float> below;
  EXPECT_EQ(update(norm * 1.01, rollout, above).grad_norm, norm);
  EXPECT_EQ(update(norm * 0.99, rollout, below).grad_norm, norm);
  EXPECT_EQ(above, unclipped);
  EXPECT_NE(below, unclipped);
}

TEST_F(PpoLearnerTest, ReportsTheLearningRateAndAGaussianPolicysStdOnly) {
  std::unique_ptr<PpoLearner> categorical = NewLearner(2);
  absl::StatusOr<UpdateStats> stats = categorical->Update(BanditRollout(*categorical, 1));
  ASSERT_TRUE(stats.ok()) << stats.status();
  EXPECT_EQ(stats->learning_rate, SmallConfig().learning_rate);
  EXPECT_FALSE(stats->std.has_value());

  run::PolicySpec gaussian = BanditSpec();
  gaussian.num_actions = 0;  // one continuous action in [-1, 1]
  gaussian.action_low = {-1};
  gaussian.action_high = {1};
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(gaussian, SmallConfig(), 1, 2);
  stats = learner->Update(BanditRollout(*learner, 1));
  ASSERT_TRUE(stats.ok()) << stats.status();
  ASSERT_TRUE(stats->std.has_value());
  EXPECT_NEAR(*stats->std, 1.0, 0.05);  // log_std starts at 0; one update moves it a little
  EXPECT_NE(*stats->std, 1.0);
}

TEST_F(PpoLearnerTest, SameSeedAndRolloutsGiveTheSameWeightsBitForBit) {
  std::unique_ptr<PpoLearner> a = NewLearner(5);
  std::unique_ptr<PpoLearner> b = NewLearner(5);
  std::unique_ptr<PpoLearner> other = NewLearner(6);
  EXPECT_EQ(a->Parameters(), b->Parameters());
  EXPECT_NE(a->Parameters(), other->Parameters());
  for (int update = 0; update < 3; ++update) {
    const actor::Rollout rollout = BanditRollout(*a, 100 + update);
    ASSERT_TRUE(a->Update(rollout).ok());
    ASSERT_TRUE(b->Update(rollout).ok());
  }
  EXPECT_EQ(a->Parameters(), b->Parameters());
}

TEST_F(PpoLearnerTest, LearnersUpdatingAtOnceOnTwoThreadsGetTheWeightsTheyGetAlone) {
  // As a learner hosting several runs updates them, on the pinned kernels (where the serial
  // OpenBLAS's products race between threads unless they hold BlasMutex, and the pthread
  // build's must be locked by OpenBLAS itself).
  constexpr int kUpdates = 30;  // enough for a race to show nearly every time
  const auto train = [](uint64_t seed) {
    std::unique_ptr<PpoLearner> learner = NewLearner(seed);
    for (int update = 0; update < kUpdates; ++update) {
      EXPECT_TRUE(learner->Update(BanditRollout(*learner, seed * 100 + update)).ok());
    }
    return learner->Parameters();
  };
  const std::vector<float> alone_a = train(1);
  const std::vector<float> alone_b = train(2);
  std::vector<float> together_a;
  std::vector<float> together_b;
  std::thread other([&] { together_b = train(2); });
  together_a = train(1);
  other.join();
  EXPECT_EQ(together_a, alone_a);
  EXPECT_EQ(together_b, alone_b);
}

TEST_F(PpoLearnerTest, NonFiniteRewardsAndObservationsAreRefusedAndTouchNothing) {
  std::unique_ptr<PpoLearner> learner = NewLearner(2);
  const std::vector<float> before = learner->Parameters();
  actor::Rollout rollout = BanditRollout(*learner, 7);
  rollout.rewards[37] = std::numeric_limits<float>::quiet_NaN();
  absl::Status status = learner->Update(rollout).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("reward of step 37, slot 0 is not finite (nan)"));

  rollout = BanditRollout(*learner, 7);
  rollout.inputs[5 * 12 + 2] = std::numeric_limits<float>::infinity();
  status = learner->Update(rollout).status();
  EXPECT_THAT(status.message(), HasSubstr("observation of step 12, slot 0 is not finite (inf)"));
  EXPECT_EQ(learner->Parameters(), before);
  EXPECT_EQ(learner->updates(), 0);
}

TEST_F(PpoLearnerTest, MisshapenRolloutsAreRefused) {
  std::unique_ptr<PpoLearner> learner = NewLearner(2);
  actor::Rollout rollout = BanditRollout(*learner, 7);
  rollout.actions.pop_back();
  EXPECT_THAT(learner->Update(rollout).status().message(), HasSubstr("actions"));
  rollout = BanditRollout(*learner, 7);
  rollout.truncations.push_back({.step = kSteps, .env = 0, .input = std::vector<float>(5)});
  EXPECT_THAT(learner->Update(rollout).status().message(), HasSubstr("outside the rollout"));
}

TEST_F(PpoLearnerTest, TruncatedStepsBootstrapTheFinalObservationsValue) {
  // The same rollout with and without a time-limit cut at the last step differ in what is
  // learned: the cut adds gamma * V(final observation) to that step's reward.
  std::unique_ptr<PpoLearner> plain = NewLearner(3);
  std::unique_ptr<PpoLearner> cut = NewLearner(3);
  actor::Rollout rollout = BanditRollout(*plain, 11);
  ASSERT_TRUE(plain->Update(rollout).ok());
  rollout.truncations.push_back(
      {.step = kSteps - 1, .env = 0, .input = std::vector<float>(5, 3.0f)});
  ASSERT_TRUE(cut->Update(rollout).ok());
  EXPECT_NE(plain->Parameters(), cut->Parameters());
}

TEST_F(PpoLearnerTest, SavedStateResumesExactly) {
  std::unique_ptr<PpoLearner> straight = NewLearner(4);
  std::unique_ptr<PpoLearner> resumed = NewLearner(4);
  for (int update = 0; update < 2; ++update) {
    ASSERT_TRUE(straight->Update(BanditRollout(*straight, 200 + update)).ok());
  }
  absl::StatusOr<std::string> state = straight->SaveState();
  ASSERT_TRUE(state.ok()) << state.status();
  ASSERT_TRUE(resumed->LoadState(*state).ok());
  EXPECT_EQ(resumed->Parameters(), straight->Parameters());  // not the fresh weights any more
  EXPECT_EQ(resumed->updates(), 2);
  // Adam's moments came along: the next updates agree too.
  for (int update = 2; update < 4; ++update) {
    const actor::Rollout rollout = BanditRollout(*straight, 200 + update);
    ASSERT_TRUE(straight->Update(rollout).ok());
    ASSERT_TRUE(resumed->Update(rollout).ok());
  }
  EXPECT_EQ(resumed->Parameters(), straight->Parameters());

  EXPECT_EQ(NewLearner(5)->LoadState(*state).code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(resumed->LoadState("not a checkpoint").code(), absl::StatusCode::kDataLoss);
  std::string truncated = *state;
  truncated.resize(truncated.size() / 2);
  EXPECT_EQ(resumed->LoadState(truncated).code(), absl::StatusCode::kDataLoss);
}

TEST_F(PpoLearnerTest, ConfigGuardsAreSb3s) {
  run::PpoConfig config;
  config.batch_size = 1;
  EXPECT_THAT(PpoLearner::Create(BanditSpec(), config, 1, 0).status().message(),
              HasSubstr("batch_size"));
  config = run::PpoConfig{.learning_rate = -1e-3};
  EXPECT_THAT(PpoLearner::Create(BanditSpec(), config, 1, 0).status().message(),
              HasSubstr("learning_rate"));
  config = run::PpoConfig{.n_steps = 1};
  EXPECT_THAT(PpoLearner::Create(BanditSpec(), config, 1, 0).status().message(),
              HasSubstr("n_steps * n_envs"));
}

}  // namespace
}  // namespace dcs::learner
