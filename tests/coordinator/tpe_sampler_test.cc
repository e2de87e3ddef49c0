// Copyright 2026 The DCS Authors.
#include "coordinator/tpe_sampler.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::Pair;

run::SearchSpace Branin() {
  return {
      .parameters = {{.name = "x1", .distribution = run::FloatDistribution{.low = -5, .high = 10}},
                     {.name = "x2", .distribution = run::FloatDistribution{.low = 0, .high = 15}}}};
}

double BraninValue(const run::ParameterValues& v) {
  const double x1 = v.at("x1");
  const double x2 = v.at("x2");
  const double b = 5.1 / (4 * std::numbers::pi * std::numbers::pi);
  const double c = 5 / std::numbers::pi;
  const double t = 1 / (8 * std::numbers::pi);
  return std::pow(x2 - b * x1 * x1 + c * x1 - 6, 2) + 10 * (1 - t) * std::cos(x1) + 10;
}

// A two-stage schedule space: each stage's mode, and a sinusoid's parameters only where the
// stage is sinusoidal.
run::SearchSpace Stages() {
  run::SearchSpace space;
  for (const std::string stage : {"stage0", "stage1"}) {
    space.parameters.push_back(
        {.name = stage + ".mode",
         .distribution = run::CategoricalDistribution{{"constant", "sinusoidal", "cosine"}}});
    const run::ParameterCondition sinusoidal{.parent = stage + ".mode", .choices = {"sinusoidal"}};
    space.parameters.push_back({.name = stage + ".amplitude",
                                .distribution = run::FloatDistribution{.low = 0.05, .high = 1},
                                .condition = sinusoidal});
    space.parameters.push_back(
        {.name = stage + ".period",
         .distribution = run::IntDistribution{.low = 10, .high = 500, .log = true},
         .condition = sinusoidal});
  }
  return space;
}

// Runs `trials` sequential trials of `sampler` on Branin; the best value after each.
std::vector<double> BestSoFar(const Sampler& sampler, int trials) {
  std::vector<StudyTrial> history;
  std::vector<double> best;
  for (int number = 0; number < trials; ++number) {
    StudyTrial trial{.number = number, .state = TrialState::kComplete};
    trial.values = sampler.Sample(Branin(), history, number);
    trial.value = BraninValue(trial.values);
    history.push_back(trial);
    best.push_back(best.empty() ? trial.value : std::min(best.back(), trial.value));
  }
  return best;
}

TEST(TpeSamplerTest, StartupTrialsAreTheRandomSamplersOnes) {
  const auto tpe = MakeTpeSampler(5, Direction::kMinimize, TpeOptions{});
  const auto random = MakeRandomSampler(5);
  std::vector<StudyTrial> history;
  for (int number = 0; number < 12; ++number) {
    const run::ParameterValues values = tpe->Sample(Branin(), history, number);
    if (number < 10) {
      EXPECT_EQ(values, random->Sample(Branin(), history, number)) << number;
    } else {
      EXPECT_NE(values, random->Sample(Branin(), history, number)) << number;
    }
    history.push_back({.number = number,
                       .state = TrialState::kComplete,
                       .value = BraninValue(values),
                       .values = values});
  }
}

TEST(TpeSamplerTest, FailedAndRunningTrialsDoNotCountTowardsStartup) {
  const auto tpe = MakeTpeSampler(5, Direction::kMinimize, TpeOptions{.startup_trials = 2});
  const auto random = MakeRandomSampler(5);
  const std::vector<StudyTrial> history = {
      {.number = 0, .state = TrialState::kComplete, .value = 3, .values = {{"x1", 1}, {"x2", 2}}},
      {.number = 1, .state = TrialState::kFailed, .values = {{"x1", 2}, {"x2", 2}}},
      {.number = 2, .state = TrialState::kRunning, .values = {{"x1", 3}, {"x2", 2}}}};
  EXPECT_EQ(tpe->Sample(Branin(), history, 3), random->Sample(Branin(), history, 3));
}

TEST(TpeSamplerTest, IsAFunctionOfSeedNumberAndHistory) {
  const auto a = MakeTpeSampler(1, Direction::kMinimize, TpeOptions{});
  const auto b = MakeTpeSampler(1, Direction::kMinimize, TpeOptions{});
  EXPECT_EQ(BestSoFar(*a, 30), BestSoFar(*b, 30));
  EXPECT_NE(BestSoFar(*a, 30), BestSoFar(*MakeTpeSampler(2, Direction::kMinimize, {}), 30));
}

// Not the benchmark (bench/study/), a sanity check: over 9 seeds, TPE's median best after 60
// Branin trials is better than random search's.
TEST(TpeSamplerTest, FindsBetterBraninValuesThanRandomSearch) {
  std::vector<double> tpe;
  std::vector<double> random;
  for (uint64_t seed = 0; seed < 9; ++seed) {
    tpe.push_back(BestSoFar(*MakeTpeSampler(seed, Direction::kMinimize, {}), 60).back());
    random.push_back(BestSoFar(*MakeRandomSampler(seed), 60).back());
  }
  std::sort(tpe.begin(), tpe.end());
  std::sort(random.begin(), random.end());
  EXPECT_LT(tpe[4], random[4]);
  EXPECT_LT(tpe[4], 0.398 + 0.5);  // f* = 0.3979
}

TEST(TpeSamplerTest, MaximisingPrefersTheHighValues) {
  // One parameter; the objective is x itself. Maximising, TPE should sample high x.
  const run::SearchSpace space{{{.name = "x", .distribution = run::FloatDistribution{0, 1}}}};
  for (const Direction direction : {Direction::kMinimize, Direction::kMaximize}) {
    const auto tpe = MakeTpeSampler(3, direction, TpeOptions{});
    std::vector<StudyTrial> history;
    double late_mean = 0;
    for (int number = 0; number < 40; ++number) {
      const run::ParameterValues values = tpe->Sample(space, history, number);
      if (number >= 30) late_mean += values.at("x") / 10;
      history.push_back({.number = number,
                         .state = TrialState::kComplete,
                         .value = values.at("x"),
                         .values = values});
    }
    if (direction == Direction::kMaximize) {
      EXPECT_GT(late_mean, 0.75);
    } else {
      EXPECT_LT(late_mean, 0.25);
    }
  }
}

TEST(TpeSamplerTest, ConditionalParametersExistOnlyWithTheirParentsChoice) {
  for (const TpeOptions& options : {TpeOptions{}, TpeOptions{.parzen = {.multivariate = true}},
                                    TpeOptions{.parzen = {.multivariate = true}, .group = true}}) {
    const auto tpe = MakeTpeSampler(11, Direction::kMaximize, options);
    const run::SearchSpace space = Stages();
    std::vector<StudyTrial> history;
    for (int number = 0; number < 30; ++number) {
      const run::ParameterValues values = tpe->Sample(space, history, number);
      for (const std::string stage : {"stage0", "stage1"}) {
        const bool sinusoidal = values.at(stage + ".mode") == 1;
        EXPECT_EQ(values.contains(stage + ".amplitude"), sinusoidal);
        EXPECT_EQ(values.contains(stage + ".period"), sinusoidal);
      }
      for (const auto& [name, value] : values) {
        const auto& p = *std::find_if(space.parameters.begin(), space.parameters.end(),
                                      [&](const auto& q) { return q.name == name; });
        EXPECT_TRUE(run::Contains(p.distribution, value)) << name << " " << value;
      }
      // Rewarded: sinusoidal first stages with a long period.
      const double value = values.contains("stage0.period") ? values.at("stage0.period") : 0;
      history.push_back(
          {.number = number, .state = TrialState::kComplete, .value = value, .values = values});
    }
  }
}

TEST(GammaTest, IsATenthRoundedUpAtMostTwentyFive) {
  EXPECT_EQ(Gamma(0), 0);
  EXPECT_EQ(Gamma(1), 1);
  EXPECT_EQ(Gamma(10), 1);
  EXPECT_EQ(Gamma(11), 2);
  EXPECT_EQ(Gamma(250), 25);
  EXPECT_EQ(Gamma(1000), 25);
}

std::vector<int64_t> Numbers(const std::vector<const StudyTrial*>& trials) {
  std::vector<int64_t> numbers;
  for (const StudyTrial* t : trials) numbers.push_back(t->number);
  return numbers;
}

TEST(SplitTrialsTest, BestCompleteThenDeepestPrunedBelowRunningAbove) {
  const std::vector<StudyTrial> trials = {
      {.number = 0, .state = TrialState::kComplete, .value = 5},
      {.number = 1, .state = TrialState::kPruned, .reported = {{1, 0.5}, {3, 9.0}}},
      {.number = 2, .state = TrialState::kComplete, .value = 1},
      {.number = 3, .state = TrialState::kRunning},
      {.number = 4, .state = TrialState::kPruned, .reported = {{3, 2.0}}},
      {.number = 5, .state = TrialState::kPruned},
      {.number = 6, .state = TrialState::kPruned, .reported = {{1, 0.1}}}};
  std::vector<const StudyTrial*> history;
  for (const StudyTrial& t : trials) history.push_back(&t);

  Split split = SplitTrials(history, 1, Direction::kMinimize);
  EXPECT_THAT(Numbers(split.below), ElementsAre(2));
  EXPECT_THAT(Numbers(split.above), ElementsAre(0, 1, 3, 4, 5, 6));
  // Both complete trials, then the pruned ones at step 3 by last value: 4 (2.0) before 1 (9.0).
  split = SplitTrials(history, 3, Direction::kMinimize);
  EXPECT_THAT(Numbers(split.below), ElementsAre(0, 2, 4));
  split = SplitTrials(history, 3, Direction::kMaximize);
  EXPECT_THAT(Numbers(split.below), ElementsAre(0, 1, 2));
  // Then step 1, and last the pruned trial that reported nothing.
  split = SplitTrials(history, 5, Direction::kMinimize);
  EXPECT_THAT(Numbers(split.below), ElementsAre(0, 1, 2, 4, 6));
  split = SplitTrials(history, 9, Direction::kMinimize);
  EXPECT_THAT(Numbers(split.below), ElementsAre(0, 1, 2, 4, 5, 6));
  EXPECT_THAT(Numbers(split.above), ElementsAre(3));
}

TEST(GroupParametersTest, ParametersThatAlwaysOccurTogetherFormAGroup) {
  const auto trial = [](int64_t number, std::vector<std::string> names) {
    StudyTrial t{.number = number, .state = TrialState::kComplete};
    for (const std::string& name : names) t.values[name] = 0;
    return t;
  };
  const std::vector<StudyTrial> trials = {
      trial(0, {"stage0.mode", "stage1.mode", "stage0.amplitude", "stage0.period"}),
      trial(1, {"stage0.mode", "stage1.mode", "stage1.amplitude", "stage1.period"}),
      trial(2, {"stage0.mode", "stage1.mode"})};
  std::vector<const StudyTrial*> finished;
  for (const StudyTrial& t : trials) finished.push_back(&t);
  EXPECT_THAT(GroupParameters(Stages(), finished),
              ElementsAre(ElementsAre("stage0.mode", "stage1.mode"),
                          ElementsAre("stage0.amplitude", "stage0.period"),
                          ElementsAre("stage1.amplitude", "stage1.period")));
}

// Ten finished trials, then six asked while none has finished: without the liar they draw on the
// same history (and differ only by their streams); with it each sees the running ones as poor.
double SpreadOfTrialsRunningAtOnce(bool constant_liar) {
  const run::SearchSpace space{{{.name = "x", .distribution = run::FloatDistribution{0, 1}}}};
  const auto tpe =
      MakeTpeSampler(4, Direction::kMinimize, TpeOptions{.constant_liar = constant_liar});
  std::vector<StudyTrial> history;
  for (int number = 0; number < 10; ++number) {
    const double x = (number + 0.5) / 10;
    history.push_back({.number = number,
                       .state = TrialState::kComplete,
                       .value = std::abs(x - 0.3),
                       .values = {{"x", x}}});
  }
  std::vector<double> xs;
  for (int number = 10; number < 16; ++number) {
    const run::ParameterValues values = tpe->Sample(space, history, number);
    history.push_back({.number = number, .state = TrialState::kRunning, .values = values});
    xs.push_back(values.at("x"));
  }
  double spread = 0;  // mean distance between two of them
  for (const double a : xs) {
    for (const double b : xs) spread += std::abs(a - b) / (xs.size() * (xs.size() - 1));
  }
  return spread;
}

TEST(TpeSamplerTest, TheConstantLiarSpreadsTrialsRunningAtOnce) {
  EXPECT_GT(SpreadOfTrialsRunningAtOnce(true), 1.5 * SpreadOfTrialsRunningAtOnce(false));
}

}  // namespace
}  // namespace dcs::coordinator
