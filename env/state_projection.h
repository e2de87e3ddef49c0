// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_STATE_PROJECTION_H_
#define DCS_ENV_STATE_PROJECTION_H_

// A discretised view of an environment's observation, as the paper's coverage diagnostic cuts
// the state space into cells (docs/reference.md, "Coverage"): some observation dimensions, each cut
// into `bins` equal bins over [low, high]. A value outside the range falls into the bin at its end,
// as the reference tracker's `digitize(v) - 1` clamped to [0, bins - 1]. Each environment with
// vector observations declares the paper's projections (`Env::CoverageProjections()`). Plain data
// and pure functions; thread-safe.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"

namespace dcs::env {

struct StateProjection {
  std::string name;
  std::vector<int> dims;  // indices into the observation
  int bins = 0;           // per dimension
  std::vector<double> low;   // per dimension
  std::vector<double> high;  // per dimension
};

// bins^dims: the number of cells.
int64_t NumCells(const StateProjection& projection);

// The cell `observation` falls in, in [0, NumCells): the bin of dims[0] varies slowest. A NaN
// falls into the last bin, as numpy's digitize puts it past the last edge.
// REQUIRES: ValidateProjection(projection, observation.size()) is OK.
int64_t CellOf(const StateProjection& projection, std::span<const float> observation);

// OK if the projection has a name, one to eight dimensions, each an index below
// `observation_size` and used once, low < high (finite) per dimension, and 1 to 1000 bins;
// INVALID_ARGUMENT naming what is wrong otherwise.
absl::Status ValidateProjection(const StateProjection& projection, int observation_size);

}  // namespace dcs::env

#endif  // DCS_ENV_STATE_PROJECTION_H_
