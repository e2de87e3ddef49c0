// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_COVERAGE_H_
#define DCS_ENV_COVERAGE_H_

// State-space coverage, the paper's diagnostic (spec/schedules.md §11): each state dimension is
// cut into equal bins over a fixed interval, and coverage is the fraction of the hypergrid's
// cells a run visited. Values outside an interval fall into its edge bins. Thread-compatible.

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"

namespace dcs::env {

struct CoverageAxis {
  double lo = 0;
  double hi = 1;
  int bins = 12;
};

class CoverageGrid {
 public:
  // INVALID_ARGUMENT unless every axis is finite with lo < hi and bins >= 1, and the grid has
  // at most 2^30 cells.
  static absl::StatusOr<CoverageGrid> Create(std::vector<CoverageAxis> axes);

  // The paper's CartPole grid: 12 bins per dimension over its "physically plausible ranges"
  // x [-2.5, 2.5] m, x_dot [-3.5, 3.5] m/s, theta [-0.30, 0.30] rad, theta_dot [-4, 4] rad/s
  // (12^4 = 20,736 cells).
  static CoverageGrid CartPolePaper();

  // Marks the cell of `state` (one value per axis) visited; true if it was not before.
  bool Visit(std::span<const float> state);

  int64_t visited_cells() const { return visited_count_; }
  int64_t total_cells() const { return static_cast<int64_t>(visited_.size()); }
  double fraction() const {
    return static_cast<double>(visited_count_) / static_cast<double>(visited_.size());
  }

 private:
  explicit CoverageGrid(std::vector<CoverageAxis> axes, int64_t cells)
      : axes_(std::move(axes)), visited_(cells, false) {}

  std::vector<CoverageAxis> axes_;
  std::vector<bool> visited_;
  int64_t visited_count_ = 0;
};

// Coverage per training window of `window_steps` environment steps, as the paper reports it
// (e.g. 0-50k, 50-100k, 100-150k): the cells first found in each window, and the cumulative
// coverage at its end.
class CoverageTracker {
 public:
  struct Window {
    int64_t first_step = 0;
    int64_t steps = 0;
    int64_t new_cells = 0;
    double new_fraction = 0;         // new_cells / total cells
    double cumulative_fraction = 0;  // coverage at the window's end
  };

  // REQUIRES: window_steps > 0.
  CoverageTracker(CoverageGrid grid, int64_t window_steps)
      : grid_(std::move(grid)), window_steps_(window_steps) {}

  // Counts one environment step in `state`.
  void Add(std::span<const float> state);

  const std::vector<Window>& windows() const { return windows_; }
  const CoverageGrid& grid() const { return grid_; }

 private:
  CoverageGrid grid_;
  const int64_t window_steps_;
  int64_t steps_ = 0;
  std::vector<Window> windows_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_COVERAGE_H_
