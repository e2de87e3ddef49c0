// Copyright 2026 The DCS Authors.
#include "env/coverage.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace dcs::env {

absl::StatusOr<CoverageGrid> CoverageGrid::Create(std::vector<CoverageAxis> axes) {
  if (axes.empty()) return absl::InvalidArgumentError("a coverage grid needs an axis");
  int64_t cells = 1;
  for (size_t i = 0; i < axes.size(); ++i) {
    const CoverageAxis& axis = axes[i];
    if (!std::isfinite(axis.lo) || !std::isfinite(axis.hi) || axis.lo >= axis.hi ||
        axis.bins < 1) {
      return absl::InvalidArgumentError(
          absl::StrCat("coverage axis ", i, " must be finite with lo < hi and bins >= 1, got [",
                       axis.lo, ", ", axis.hi, "] with ", axis.bins, " bins"));
    }
    cells *= axis.bins;
    if (cells > (int64_t{1} << 30)) {
      return absl::InvalidArgumentError("a coverage grid may have at most 2^30 cells");
    }
  }
  return CoverageGrid(std::move(axes), cells);
}

CoverageGrid CoverageGrid::CartPolePaper() {
  return *Create({{-2.5, 2.5, 12}, {-3.5, 3.5, 12}, {-0.30, 0.30, 12}, {-4.0, 4.0, 12}});
}

bool CoverageGrid::Visit(std::span<const float> state) {
  int64_t cell = 0;
  for (size_t i = 0; i < axes_.size(); ++i) {
    const CoverageAxis& axis = axes_[i];
    const double position = (state[i] - axis.lo) / (axis.hi - axis.lo) * axis.bins;
    // NaN lands in bin 0, like a value below the interval.
    const int bin = std::isnan(position) ? 0
                                         : static_cast<int>(std::clamp(
                                               std::floor(position), 0.0, axis.bins - 1.0));
    cell = cell * axis.bins + bin;
  }
  if (visited_[cell]) return false;
  visited_[cell] = true;
  ++visited_count_;
  return true;
}

void CoverageTracker::Add(std::span<const float> state) {
  if (steps_ % window_steps_ == 0) windows_.push_back({.first_step = steps_});
  Window& window = windows_.back();
  ++steps_;
  ++window.steps;
  if (grid_.Visit(state)) {
    ++window.new_cells;
    window.new_fraction =
        static_cast<double>(window.new_cells) / static_cast<double>(grid_.total_cells());
  }
  window.cumulative_fraction = grid_.fraction();
}

}  // namespace dcs::env
