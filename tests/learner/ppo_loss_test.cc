// Copyright 2026 The DCS Authors.
#include "learner/ppo_loss.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "gtest/gtest.h"

namespace dcs::learner {
namespace {

const double kHalfLog2Pi = 0.5 * std::log(2 * std::numbers::pi);

run::PolicySpec TwoActions() { return {.observation_size = 4, .num_actions = 2}; }

TEST(PpoLossTest, CategoricalLogProbIsTheLogSoftmaxOfTheChosenLogit) {
  const std::vector<float> logits = {0.5f, -1.0f, 2.0f, 2.0f};  // two samples
  std::vector<float> log_probs(2);
  ActionLogProbs(TwoActions(), logits, {}, std::vector<float>{1, 0}, log_probs);
  EXPECT_NEAR(log_probs[0], -1.5 - std::log(1 + std::exp(-1.5)), 1e-6);
  EXPECT_NEAR(log_probs[1], -std::log(2.0), 1e-6);
}

TEST(PpoLossTest, GaussianLogProbAndEntropyAreSummedOverDimensions) {
  const run::PolicySpec spec{.observation_size = 1, .num_actions = 0, .action_size = 4};
  const std::vector<float> mean = {0.1f, -0.2f, 0.0f, 0.4f};
  const std::vector<float> log_std(4, -0.5f);
  std::vector<float> action = mean;
  for (float& a : action) a += 0.3f;
  std::vector<float> log_prob(1);
  ActionLogProbs(spec, mean, log_std, action, log_prob);
  // Each dimension: N(mean, e^-0.5) at mean + 0.3.
  const double sigma = std::exp(-0.5);
  const double per_dim = -0.5 * (0.3 / sigma) * (0.3 / sigma) - std::log(sigma) - kHalfLog2Pi;
  EXPECT_NEAR(log_prob[0], 4 * per_dim, 1e-5);

  std::vector<float> d_head(4);
  std::vector<float> d_value(1);
  std::vector<float> d_log_std(4);
  const std::vector<float> zero = {0.0f};
  const PpoLoss loss = ComputePpoLoss(
      spec, run::PpoConfig{},
      {.size = 1, .head = mean, .values = zero, .log_std = log_std, .actions = action,
       .advantages = zero, .returns = zero, .old_log_probs = log_prob, .old_values = zero},
      {.head = d_head, .values = d_value, .log_std = d_log_std});
  EXPECT_NEAR(loss.entropy, -4 * (0.5 + kHalfLog2Pi - 0.5), 1e-5);  // -mean(H)
}

// One sample of the two-action policy with equal logits (log p = log 1/2) taking action 0,
// given its old log-probability, advantage, value (also its old value) and return.
struct OneSample {
  PpoLoss loss;
  std::vector<float> d_logits = std::vector<float>(2);
  float d_value = 0;
};
OneSample Evaluate(float old_log_prob, float advantage, float value, float ret) {
  OneSample s;
  const std::vector<float> logits = {0, 0};
  const float action = 0;
  s.loss = ComputePpoLoss(
      TwoActions(), run::PpoConfig{},
      {.size = 1, .head = logits, .values = {&value, 1}, .actions = {&action, 1},
       .advantages = {&advantage, 1}, .returns = {&ret, 1},
       .old_log_probs = {&old_log_prob, 1}, .old_values = {&value, 1}},
      {.head = s.d_logits, .values = {&s.d_value, 1}});
  return s;
}

TEST(PpoLossTest, TheSurrogateIsClippedOnlyAgainstTheAdvantage) {
  const float half = std::log(0.5f);
  // ratio 1.5 with a positive advantage: clipped at 1.2, no gradient, counted as clipped.
  OneSample up = Evaluate(half - std::log(1.5f), 2.0f, 0, 0);
  EXPECT_NEAR(up.loss.policy, -2.0 * 1.2, 1e-6);
  EXPECT_EQ(up.d_logits[0], 0.0f);
  EXPECT_EQ(up.loss.clip_fraction, 1.0);
  EXPECT_NEAR(up.loss.approx_kl, 0.5 - std::log(1.5), 1e-6);
  // ratio 1.5 with a negative advantage: the unclipped term is the smaller and carries the
  // gradient: d(-A r)/d logit_0 = -A r (1 - p_0).
  OneSample down = Evaluate(half - std::log(1.5f), -2.0f, 0, 0);
  EXPECT_NEAR(down.loss.policy, 2.0 * 1.5, 1e-6);
  EXPECT_NEAR(down.d_logits[0], 2.0 * 1.5 * 0.5, 1e-6);
  EXPECT_NEAR(down.d_logits[1], -2.0 * 1.5 * 0.5, 1e-6);
  // Inside the clip range: the plain policy gradient.
  OneSample inside = Evaluate(half, 1.0f, 0, 0);
  EXPECT_NEAR(inside.d_logits[0], -0.5, 1e-6);
  EXPECT_EQ(inside.loss.clip_fraction, 0.0);
}

TEST(PpoLossTest, ValueLossIsTheMeanSquaredErrorScaledByVfCoef) {
  OneSample s = Evaluate(std::log(0.5f), 0, 1.5f, 0.5f);
  EXPECT_NEAR(s.loss.value, 1.0, 1e-6);
  EXPECT_NEAR(s.d_value, 0.5 * 2 * 1.0, 1e-6);
  EXPECT_NEAR(s.loss.total, 0.5 * 1.0 + s.loss.policy, 1e-6);
}

TEST(PpoLossTest, ClippedValuesPassNoGradientOutsideTheClip) {
  // With clip_range_vf 0.2: a value equal to its old value (the gradient passes), and one
  // 0.5 above it (predicted as old + 0.2: no gradient).
  const run::PolicySpec spec = TwoActions();
  const run::PpoConfig config{.clip_range_vf = 0.2};
  const std::vector<float> logits = {0, 0, 0, 0};
  const std::vector<float> actions = {0, 0};
  const std::vector<float> values = {1.0f, 1.5f};
  const std::vector<float> old_values = {1.0f, 1.0f};
  const std::vector<float> returns = {0.0f, 0.0f};
  const std::vector<float> zeros = {0.0f, 0.0f};
  const std::vector<float> old_log_probs(2, std::log(0.5f));
  std::vector<float> d_logits(4);
  std::vector<float> d_values(2);
  const PpoLoss loss = ComputePpoLoss(
      spec, config,
      {.size = 2, .head = logits, .values = values, .actions = actions, .advantages = zeros,
       .returns = returns, .old_log_probs = old_log_probs, .old_values = old_values},
      {.head = d_logits, .values = d_values});
  EXPECT_NEAR(loss.value, (1.0 + 1.2 * 1.2) / 2, 1e-6);
  EXPECT_NEAR(d_values[0], 0.5 * 2 * 1.0 / 2, 1e-6);
  EXPECT_EQ(d_values[1], 0.0f);
}

}  // namespace
}  // namespace dcs::learner
