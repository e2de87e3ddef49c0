// Copyright 2026 The DCS Authors.
#include "env/cartpole.h"

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "common/random.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

struct GoldenRow {
  int init;
  int t;
  int action;
  CartPoleState state;
  double reward;
  bool terminated;
};

// tests/env/data/cartpole_golden_default.csv: Gymnasium 1.4.0 trajectories, default context.
std::vector<GoldenRow> ReadGolden() {
  std::ifstream file(DCS_TEST_DATA_DIR "/cartpole_golden_default.csv");
  std::vector<GoldenRow> rows;
  std::string line;
  std::getline(file, line);  // header
  while (std::getline(file, line)) {
    const std::vector<std::string> f = absl::StrSplit(line, ',');
    if (f.size() != 10) continue;
    rows.push_back({std::atoi(f[1].c_str()), std::atoi(f[2].c_str()), std::atoi(f[3].c_str()),
                    {std::strtod(f[4].c_str(), nullptr), std::strtod(f[5].c_str(), nullptr),
                     std::strtod(f[6].c_str(), nullptr), std::strtod(f[7].c_str(), nullptr)},
                    std::strtod(f[8].c_str(), nullptr), f[9] == "1"});
  }
  return rows;
}

// The golden file was produced with a cosine that is one ulp above the correctly rounded value
// at some angles (at theta = 0.005853658536585366, init 0 step 3: 0.9999828673897899 where the
// exact cosine rounds to ...898, which glibc returns), most likely numpy's SIMD path. So no
// port with a correctly rounded std::cos agrees bit for bit; ours stays within 4e-14 relative
// over all 1000 steps, before and after termination (the spec allows about 1e-12). Rewards and
// termination flags agree exactly.
void ExpectClose(double actual, double expected, const char* what) {
  EXPECT_NEAR(actual, expected, 1e-13 * std::abs(expected) + 1e-300) << what;
}

TEST(CartPoleTest, ReproducesGymnasiumGoldenTrajectories) {
  const std::vector<GoldenRow> rows = ReadGolden();
  ASSERT_EQ(rows.size(), 1005u);
  CartPole env;
  std::array<float, 4> observation;
  int compared = 0;
  for (const GoldenRow& row : rows) {
    SCOPED_TRACE(testing::Message() << "init " << row.init << " t " << row.t);
    if (row.t == 0) {
      env.ResetTo(row.state, observation);
      continue;
    }
    const std::array<int32_t, 1> action = {row.action};
    const StepResult result = env.Step(action, observation);
    ExpectClose(env.state().x, row.state.x, "x");
    ExpectClose(env.state().x_dot, row.state.x_dot, "x_dot");
    ExpectClose(env.state().theta, row.state.theta, "theta");
    ExpectClose(env.state().theta_dot, row.state.theta_dot, "theta_dot");
    EXPECT_EQ(result.reward, row.reward);
    EXPECT_EQ(result.terminated, row.terminated);
    EXPECT_FALSE(result.truncated);
    EXPECT_EQ(observation[2], static_cast<float>(env.state().theta));
    ++compared;
  }
  EXPECT_EQ(compared, 1000);
}

TEST(CartPoleTest, ResetMatchesGymnasiumSeeds) {
  // Gymnasium's CartPole.reset: reset(seed=0) with Gymnasium's +-0.05, and seed 123 with +-0.1.
  CartPole env;
  std::array<float, 4> observation;
  env.SetFeature(CartPole::kInitialStateLower, -0.05);
  env.SetFeature(CartPole::kInitialStateUpper, 0.05);
  Random seed0(0);
  env.Reset(seed0, observation);
  EXPECT_EQ(env.state().x, 0.013696168732145436);
  EXPECT_EQ(env.state().x_dot, -0.02302132862361297);
  EXPECT_EQ(env.state().theta, -0.045902647606380534);
  EXPECT_EQ(env.state().theta_dot, -0.04834723644714709);

  env.SetFeature(CartPole::kInitialStateLower, -0.1);
  env.SetFeature(CartPole::kInitialStateUpper, 0.1);
  Random seed123(123);
  env.Reset(seed123, observation);
  EXPECT_EQ(env.state().x, 0.036470372649628685);
  EXPECT_EQ(env.state().x_dot, -0.08923579623955546);
  EXPECT_EQ(env.state().theta, -0.05592802544547773);
  EXPECT_EQ(env.state().theta_dot, -0.06312563786026607);
  EXPECT_EQ(observation[0], static_cast<float>(0.036470372649628685));
}

TEST(CartPoleTest, TruncatesAtFiveHundredSteps) {
  CartPole env;
  std::array<float, 4> observation;
  env.ResetTo({}, observation);
  // Truncation counts steps whatever the state (stepping after termination is allowed).
  StepResult result;
  for (int step = 1; step <= CartPole::kMaxEpisodeSteps; ++step) {
    const std::array<int32_t, 1> action = {step % 2};
    result = env.Step(action, observation);
    ASSERT_EQ(result.truncated, step == CartPole::kMaxEpisodeSteps) << step;
  }
  env.ResetTo({}, observation);
  const std::array<int32_t, 1> action = {0};
  EXPECT_FALSE(env.Step(action, observation).truncated);
}

TEST(CartPoleTest, RewardIsZeroAfterTheFirstTerminatingStepUntilReset) {
  CartPole env;
  std::array<float, 4> observation;
  env.ResetTo({.x = 2.39, .x_dot = 1.0}, observation);
  const std::array<int32_t, 1> right = {1};
  const StepResult first = env.Step(right, observation);
  ASSERT_TRUE(first.terminated);
  EXPECT_EQ(first.reward, 1.0);
  const StepResult second = env.Step(right, observation);
  EXPECT_TRUE(second.terminated);
  EXPECT_EQ(second.reward, 0.0);
  env.ResetTo({.x = 2.39, .x_dot = 1.0}, observation);
  EXPECT_EQ(env.Step(right, observation).reward, 1.0);
}

TEST(CartPoleTest, AFeatureChangedMidEpisodeActsOnTheNextStepWithDerivedQuantities) {
  // Two poles from the same state, one lengthened mid-episode: the next step must equal a
  // fresh environment built with that length from the start (so the derived pole mass-length
  // was recomputed), and differ from the unchanged one.
  CartPole changed;
  CartPole reference;
  CartPole unchanged;
  std::array<float, 4> observation;
  const CartPoleState start = {.x = 0.1, .x_dot = 0.2, .theta = 0.05, .theta_dot = -0.1};
  const std::array<int32_t, 1> push = {1};
  changed.ResetTo(start, observation);
  unchanged.ResetTo(start, observation);
  changed.Step(push, observation);
  unchanged.Step(push, observation);
  changed.SetFeature(CartPole::kLength, 1.3);
  changed.SetFeature(CartPole::kMassPole, 0.4);
  reference.SetFeature(CartPole::kLength, 1.3);
  reference.SetFeature(CartPole::kMassPole, 0.4);
  reference.ResetTo(changed.state(), observation);
  changed.Step(push, observation);
  reference.Step(push, observation);
  unchanged.Step(push, observation);
  EXPECT_EQ(changed.state().theta_dot, reference.state().theta_dot);
  EXPECT_EQ(changed.state().x_dot, reference.state().x_dot);
  EXPECT_NE(changed.state().theta_dot, unchanged.state().theta_dot);
}

TEST(CartPoleTest, ForceMagnitudeScalesTheCartAcceleration) {
  // From rest and upright the pole stays at theta = 0 for two steps, where the dynamics are
  // linear in the force: twice the force, twice the cart velocity.
  CartPole weak;
  CartPole strong;
  std::array<float, 4> observation;
  strong.SetFeature(CartPole::kForceMag, 20.0);
  weak.ResetTo({}, observation);
  strong.ResetTo({}, observation);
  const std::array<int32_t, 1> push = {1};
  weak.Step(push, observation);
  strong.Step(push, observation);
  weak.Step(push, observation);
  strong.Step(push, observation);
  EXPECT_NEAR(strong.state().x_dot, 2 * weak.state().x_dot, 1e-12);
}

TEST(CartPoleTest, ValidateContextRejectsOutOfBoundsAndCrossedResetBounds) {
  std::vector<double> context = CartPole::Features().Defaults();
  EXPECT_TRUE(CartPole::ValidateContext(context).ok());
  context[CartPole::kLength] = 6.0;
  EXPECT_THAT(CartPole::ValidateContext(context).message(), testing::HasSubstr("length"));
  context = CartPole::Features().Defaults();
  context[CartPole::kInitialStateLower] = 0.2;
  EXPECT_EQ(CartPole::ValidateContext(context).code(), absl::StatusCode::kInvalidArgument);
  context = CartPole::Features().Defaults();
  context[CartPole::kGravity] = std::nan("");
  EXPECT_EQ(CartPole::ValidateContext(context).code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::env
