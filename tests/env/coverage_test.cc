// Copyright 2026 The DCS Authors.
//
// The coverage diagnostic (spec/schedules.md §11, env/coverage.h).

#include "env/coverage.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "absl/status/statusor.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::HasSubstr;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

CoverageGrid Grid(std::vector<CoverageAxis> axes) {
  absl::StatusOr<CoverageGrid> grid = CoverageGrid::Create(std::move(axes));
  EXPECT_TRUE(grid.ok()) << grid.status();
  return *std::move(grid);
}

bool Visit(CoverageGrid& grid, std::vector<float> state) { return grid.Visit(state); }

TEST(CoverageGridTest, CountsDistinctCells) {
  // 2 x 3 cells over [0, 1] x [0, 3].
  CoverageGrid grid = Grid({{.lo = 0, .hi = 1, .bins = 2}, {.lo = 0, .hi = 3, .bins = 3}});
  EXPECT_EQ(grid.total_cells(), 6);
  EXPECT_EQ(grid.visited_cells(), 0);
  EXPECT_TRUE(Visit(grid, {0.1f, 0.5f}));
  EXPECT_FALSE(Visit(grid, {0.4f, 0.9f}));  // same cell (0, 0)
  EXPECT_TRUE(Visit(grid, {0.6f, 0.5f}));   // (1, 0)
  EXPECT_TRUE(Visit(grid, {0.1f, 1.5f}));   // (0, 1)
  EXPECT_TRUE(Visit(grid, {0.1f, 2.5f}));   // (0, 2)
  EXPECT_FALSE(Visit(grid, {0.2f, 2.9f}));
  EXPECT_EQ(grid.visited_cells(), 4);
  EXPECT_DOUBLE_EQ(grid.fraction(), 4.0 / 6.0);
  // Cells (a, b) and (b, a) are distinct: the index is not symmetric.
  EXPECT_TRUE(Visit(grid, {0.6f, 1.5f}));  // (1, 1)
  EXPECT_TRUE(Visit(grid, {0.6f, 2.5f}));  // (1, 2)
  EXPECT_EQ(grid.visited_cells(), 6);
  EXPECT_DOUBLE_EQ(grid.fraction(), 1.0);
}

TEST(CoverageGridTest, BinEdgesAndClampingAtTheInterval) {
  CoverageGrid grid = Grid({{.lo = -1, .hi = 1, .bins = 4}});  // edges -1, -0.5, 0, 0.5, 1
  EXPECT_TRUE(Visit(grid, {-0.5f}));   // bin 1 (a left edge belongs to its bin)
  EXPECT_TRUE(Visit(grid, {-0.51f}));  // bin 0
  EXPECT_FALSE(Visit(grid, {-1.0f}));  // bin 0
  EXPECT_FALSE(Visit(grid, {-7.0f}));  // below the interval: the first bin
  EXPECT_FALSE(Visit(grid, {-kInf}));
  EXPECT_TRUE(Visit(grid, {0.99f}));   // bin 3
  EXPECT_FALSE(Visit(grid, {1.0f}));   // the upper bound: the last bin
  EXPECT_FALSE(Visit(grid, {250.0f})); // above: the last bin
  EXPECT_FALSE(Visit(grid, {kInf}));
  EXPECT_EQ(grid.visited_cells(), 3);
  EXPECT_TRUE(Visit(grid, {0.0f}));  // bin 2
  EXPECT_EQ(grid.visited_cells(), 4);
}

TEST(CoverageGridTest, NaNLandsInTheFirstBin) {
  // The documented choice (coverage.cc): NaN counts like a value below the interval.
  CoverageGrid grid = Grid({{.lo = 0, .hi = 1, .bins = 3}, {.lo = 0, .hi = 1, .bins = 3}});
  EXPECT_TRUE(Visit(grid, {kNaN, 0.5f}));
  EXPECT_FALSE(Visit(grid, {-3.0f, 0.5f}));
  EXPECT_FALSE(Visit(grid, {0.0f, 0.4f}));
  EXPECT_TRUE(Visit(grid, {0.5f, kNaN}));
  EXPECT_FALSE(Visit(grid, {0.5f, 0.1f}));
  EXPECT_EQ(grid.visited_cells(), 2);
}

TEST(CoverageGridTest, CartPolePaperGrid) {
  CoverageGrid grid = CoverageGrid::CartPolePaper();
  EXPECT_EQ(grid.total_cells(), 20736);  // 12^4
  // x bins are 5/12 = 0.4167 m wide over [-2.5, 2.5]: 2.1 and 2.49 share the last bin, 2.0 is
  // in the one before; theta bins are 0.05 rad wide over [-0.3, 0.3].
  EXPECT_TRUE(Visit(grid, {2.1f, 0, 0, 0}));
  EXPECT_FALSE(Visit(grid, {2.49f, 0, 0, 0}));
  EXPECT_FALSE(Visit(grid, {4.8f, 0, 0, 0}));
  EXPECT_TRUE(Visit(grid, {2.0f, 0, 0, 0}));
  EXPECT_TRUE(Visit(grid, {0, 0, 0.26f, 0}));
  EXPECT_FALSE(Visit(grid, {0, 0, 0.29f, 0}));
  EXPECT_FALSE(Visit(grid, {0, 0, 0.418f, 0}));  // beyond the plausible range: edge bin
  EXPECT_TRUE(Visit(grid, {0, 0, 0.24f, 0}));
  // x_dot bins 7/12 wide over [-3.5, 3.5], theta_dot 8/12 wide over [-4, 4].
  EXPECT_TRUE(Visit(grid, {0, 0, 0, 0}));
  EXPECT_FALSE(Visit(grid, {0, 0.5f, 0, 0}));  // 0 and 0.5 share [0, 0.583)
  EXPECT_TRUE(Visit(grid, {0, 0.6f, 0, 0}));
  EXPECT_FALSE(Visit(grid, {0, 0, 0, 0.6f}));  // 0 and 0.6 share [0, 0.667)
  EXPECT_TRUE(Visit(grid, {0, 0, 0, 0.7f}));
  EXPECT_EQ(grid.visited_cells(), 7);
  EXPECT_DOUBLE_EQ(grid.fraction(), 7.0 / 20736.0);
}

TEST(CoverageGridTest, CreateErrors) {
  EXPECT_FALSE(CoverageGrid::Create({}).ok());
  EXPECT_THAT(CoverageGrid::Create({{.lo = 1, .hi = 1, .bins = 3}}).status().message(),
              HasSubstr("axis 0"));
  EXPECT_THAT(
      CoverageGrid::Create({{.lo = 0, .hi = 1, .bins = 3}, {.lo = 2, .hi = 1, .bins = 3}})
          .status()
          .message(),
      HasSubstr("axis 1"));
  EXPECT_FALSE(CoverageGrid::Create({{.lo = 0, .hi = 1, .bins = 0}}).ok());
  EXPECT_FALSE(
      CoverageGrid::Create({{.lo = 0, .hi = std::numeric_limits<double>::infinity()}}).ok());
  EXPECT_FALSE(
      CoverageGrid::Create({{.lo = std::numeric_limits<double>::quiet_NaN(), .hi = 1}}).ok());
  // At most 2^30 cells: 2^15 x 2^15 is allowed, one more bin is not.
  EXPECT_TRUE(CoverageGrid::Create({{.bins = 1 << 15}, {.bins = 1 << 15}}).ok());
  EXPECT_THAT(CoverageGrid::Create({{.bins = 1 << 15}, {.bins = (1 << 15) + 1}}).status().message(),
              HasSubstr("2^30"));
}

TEST(CoverageTrackerTest, WindowsCountNewCellsAndCumulativeCoverage) {
  // 4 cells on one axis, windows of 3 steps.
  CoverageTracker tracker(Grid({{.lo = 0, .hi = 4, .bins = 4}}), 3);
  for (float x : {0.5f, 1.5f, 0.5f,    // window 1: cells 0, 1 new
                  1.5f, 0.2f, 1.2f,    // window 2: nothing new
                  2.5f, 3.5f}) {       // window 3 (partial): cells 2, 3 new
    tracker.Add(std::vector<float>{x});
  }
  const std::vector<CoverageTracker::Window>& windows = tracker.windows();
  ASSERT_EQ(windows.size(), 3u);
  EXPECT_EQ(windows[0].first_step, 0);
  EXPECT_EQ(windows[0].steps, 3);
  EXPECT_EQ(windows[0].new_cells, 2);
  EXPECT_DOUBLE_EQ(windows[0].new_fraction, 0.5);
  EXPECT_DOUBLE_EQ(windows[0].cumulative_fraction, 0.5);
  EXPECT_EQ(windows[1].first_step, 3);
  EXPECT_EQ(windows[1].steps, 3);
  EXPECT_EQ(windows[1].new_cells, 0);
  EXPECT_DOUBLE_EQ(windows[1].new_fraction, 0.0);
  EXPECT_DOUBLE_EQ(windows[1].cumulative_fraction, 0.5);
  EXPECT_EQ(windows[2].first_step, 6);
  EXPECT_EQ(windows[2].steps, 2);
  EXPECT_EQ(windows[2].new_cells, 2);
  EXPECT_DOUBLE_EQ(windows[2].new_fraction, 0.5);
  EXPECT_DOUBLE_EQ(windows[2].cumulative_fraction, 1.0);
  EXPECT_EQ(tracker.grid().visited_cells(), 4);
}

}  // namespace
}  // namespace dcs::env
