// Copyright 2026 The DCS Authors.
#include "learner/gae.h"

#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::learner {
namespace {

using ::testing::FloatEq;
using ::testing::Pointwise;

TEST(GaeTest, OneEnvironmentWithoutBoundariesByHand) {
  // gamma 0.5, lambda 0.5; V = (1, 2, 3), r = (1, 1, 1), V(next) = 4, not done.
  // delta_2 = 1 + 0.5 * 4 - 3 = 0            A_2 = 0
  // delta_1 = 1 + 0.5 * 3 - 2 = 0.5          A_1 = 0.5 + 0.25 * 0 = 0.5
  // delta_0 = 1 + 0.5 * 2 - 1 = 1            A_0 = 1 + 0.25 * 0.5 = 1.125
  const std::vector<float> rewards = {1, 1, 1};
  const std::vector<float> values = {1, 2, 3};
  const std::vector<uint8_t> starts = {1, 0, 0};
  const std::vector<float> last_values = {4};
  const std::vector<uint8_t> last_dones = {0};
  std::vector<float> advantages(3);
  std::vector<float> returns(3);
  ComputeGae({3, 1, rewards, values, starts, last_values, last_dones}, 0.5f, 0.5f, advantages,
             returns);
  EXPECT_THAT(advantages, Pointwise(FloatEq(), std::vector<float>{1.125f, 0.5f, 0.0f}));
  EXPECT_THAT(returns, Pointwise(FloatEq(), std::vector<float>{2.125f, 2.5f, 3.0f}));
}

TEST(GaeTest, AnEpisodeStartCutsTheRecursionAndADoneLastStepIgnoresTheBootstrap) {
  // Step 2 starts a new episode: step 1's delta uses no next value and carries no later gae.
  // The last step is done, so last_values must not matter.
  const std::vector<float> rewards = {1, 2, 3};
  const std::vector<float> values = {0.5f, 1, 1.5f};
  const std::vector<uint8_t> starts = {0, 0, 1};
  const std::vector<uint8_t> last_dones = {1};
  std::vector<float> advantages(3);
  std::vector<float> returns(3);
  for (float last_value : {0.0f, 1000.0f}) {
    const std::vector<float> last_values = {last_value};
    ComputeGae({3, 1, rewards, values, starts, last_values, last_dones}, 0.9f, 0.8f, advantages,
               returns);
    // A_2 = 3 - 1.5 = 1.5; A_1 = 2 - 1 = 1; A_0 = (1 + 0.9 * 1 - 0.5) + 0.72 * 1 = 2.12.
    EXPECT_THAT(advantages, Pointwise(FloatEq(), std::vector<float>{2.12f, 1.0f, 1.5f}));
  }
}

TEST(GaeTest, EnvironmentsAreIndependentColumnsOfTimeMajorBuffers) {
  // Two environments interleaved [t][e]; env 1 is env 0's data shifted, and must come out as
  // if computed alone.
  const std::vector<float> rewards = {1, 5, 1, 6, 1, 7};
  const std::vector<float> values = {1, 2, 2, 3, 3, 4};
  const std::vector<uint8_t> starts = {1, 1, 0, 0, 0, 1};
  const std::vector<float> last_values = {4, 9};
  const std::vector<uint8_t> last_dones = {0, 0};
  std::vector<float> advantages(6);
  std::vector<float> returns(6);
  ComputeGae({3, 2, rewards, values, starts, last_values, last_dones}, 0.5f, 0.5f, advantages,
             returns);
  EXPECT_THAT((std::vector<float>{advantages[0], advantages[2], advantages[4]}),
              Pointwise(FloatEq(), std::vector<float>{1.125f, 0.5f, 0.0f}));
  // Env 1: step 2 starts an episode. A_2 = 7 + 0.5 * 9 - 4 = 7.5; A_1 = 6 - 3 = 3;
  // A_0 = (5 + 0.5 * 3 - 2) + 0.25 * 3 = 5.25.
  EXPECT_THAT((std::vector<float>{advantages[1], advantages[3], advantages[5]}),
              Pointwise(FloatEq(), std::vector<float>{5.25f, 3.0f, 7.5f}));
}

}  // namespace
}  // namespace dcs::learner
