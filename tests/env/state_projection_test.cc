// Copyright 2026 The DCS Authors.
#include "env/state_projection.h"

#include <cmath>
#include <limits>
#include <vector>

#include "env/bipedal_walker.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::HasSubstr;

StateProjection OneDim(double low, double high, int bins) {
  return {.name = "x", .dims = {0}, .bins = bins, .low = {low}, .high = {high}};
}

int64_t Cell(const StateProjection& projection, double value) {
  const std::vector<float> observation = {static_cast<float>(value)};
  return CellOf(projection, observation);
}

TEST(StateProjectionTest, BinsAsNumpysDigitizeOverLinspaceEdgesClamped) {
  const StateProjection p = OneDim(-0.3, 0.3, 12);
  EXPECT_EQ(Cell(p, -0.3), 0);
  EXPECT_EQ(Cell(p, 0.0), 6);
  EXPECT_EQ(Cell(p, 0.29), 11);
  EXPECT_EQ(Cell(p, 0.3), 11);  // the last edge: past the range, clamped
  EXPECT_EQ(Cell(p, -7.0), 0);
  EXPECT_EQ(Cell(p, 7.0), 11);
  EXPECT_EQ(Cell(p, std::numeric_limits<double>::infinity()), 11);
  EXPECT_EQ(Cell(p, -std::numeric_limits<double>::infinity()), 0);
  EXPECT_EQ(Cell(p, std::nan("")), 11);  // digitize puts NaN past the last edge
}

TEST(StateProjectionTest, AValueOnAnEdgeFallsInTheBinAboveEvenWhereDivisionRoundsBelow) {
  // Over [-4, -3.9] in 8 bins, edge 5 is -4 + 5 * 0.0125 = -3.9375 exactly, but
  // (-3.9375 + 4) / 0.0125 divides to just under 5: the bin is still 5, as digitize's.
  const StateProjection p = OneDim(-4, -3.9, 8);
  const double step = (-3.9 - -4.0) / 8;
  ASSERT_EQ(-4 + 5 * step, -3.9375);
  ASSERT_LT(std::floor((-3.9375 + 4) / step), 5.0);
  EXPECT_EQ(Cell(p, -3.9375), 5);
  EXPECT_EQ(Cell(p, std::nextafter(-3.9375f, -4.0f)), 4);
}

TEST(StateProjectionTest, CellsCountTheFirstDimensionSlowest) {
  const StateProjection p{
      .name = "xy", .dims = {1, 0}, .bins = 4, .low = {0, 0}, .high = {4, 4}};
  EXPECT_EQ(NumCells(p), 16);
  // dims[0] is observation[1] = 3.5 (bin 3), dims[1] is observation[0] = 1.5 (bin 1).
  EXPECT_EQ(CellOf(p, std::vector<float>{1.5f, 3.5f}), 3 * 4 + 1);
}

TEST(StateProjectionTest, EnvironmentsDeclareThePapersProjections) {
  const std::vector<StateProjection>& cartpole = CartPole::CoverageProjections();
  ASSERT_EQ(cartpole.size(), 1u);
  EXPECT_EQ(NumCells(cartpole[0]), 20'736);
  EXPECT_EQ(cartpole[0].high, (std::vector<double>{2.5, 3.5, 0.30, 4.0}));
  int64_t walker_cells = 0;
  for (const StateProjection& p : BipedalWalker::CoverageProjections()) {
    EXPECT_TRUE(ValidateProjection(p, BipedalWalker::kObservationSize).ok()) << p.name;
    walker_cells += NumCells(p);
  }
  EXPECT_EQ(walker_cells, 30 * 30 + 12 * 12 * 12 * 12 + 15 * 15 * 15 + 30 * 30);
  EXPECT_TRUE(ValidateProjection(cartpole[0], CartPole::kObservationSize).ok());
}

TEST(StateProjectionTest, ValidationNamesWhatIsWrong) {
  StateProjection p = OneDim(0, 1, 10);
  EXPECT_TRUE(ValidateProjection(p, 4).ok());
  p.dims = {4};
  EXPECT_THAT(ValidateProjection(p, 4).message(), HasSubstr("dimension 4 is not in the"));
  p.dims = {0};
  p.bins = 0;
  EXPECT_THAT(ValidateProjection(p, 4).message(), HasSubstr("1 to 1000 bins, got 0"));
  p.bins = 10;
  p.high = {0};
  EXPECT_THAT(ValidateProjection(p, 4).message(), HasSubstr("finite low < high, got [0, 0]"));
  p = OneDim(0, 1, 10);
  p.dims = {1, 1};
  p.low = {0, 0};
  p.high = {1, 1};
  EXPECT_THAT(ValidateProjection(p, 4).message(), HasSubstr("dimension 1 is given twice"));
}

}  // namespace
}  // namespace dcs::env
