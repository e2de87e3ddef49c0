// Copyright 2026 The DCS Authors.
#include "env/state_projection.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"

namespace dcs::env {
namespace {

constexpr int kMaxDims = 8;
constexpr int kMaxBins = 1000;

// The bin of `value` over `bins` bins of [low, high]: the edges are numpy's
// linspace(low, high, bins + 1) (edge i = low + i * step, the last exactly high), and the bin is
// digitize's, clamped: the k with edge k <= value < edge k + 1, 0 below the range, bins - 1 above
// it or for a NaN.
int BinOf(double value, double low, double high, int bins) {
  if (std::isnan(value)) return bins - 1;
  const double step = (high - low) / bins;
  auto edge = [&](int i) { return i == bins ? high : low + i * step; };
  // The formula's guess, then corrected against the edges as numpy computes them.
  int k = static_cast<int>(std::clamp(std::floor((value - low) / step), -1.0,
                                      static_cast<double>(bins)));
  while (k < bins && edge(k + 1) <= value) ++k;
  while (k >= 0 && edge(k) > value) --k;
  return std::clamp(k, 0, bins - 1);
}

}  // namespace

int64_t NumCells(const StateProjection& projection) {
  int64_t cells = 1;
  for (size_t i = 0; i < projection.dims.size(); ++i) cells *= projection.bins;
  return cells;
}

int64_t CellOf(const StateProjection& projection, std::span<const float> observation) {
  int64_t cell = 0;
  for (size_t i = 0; i < projection.dims.size(); ++i) {
    cell = cell * projection.bins + BinOf(observation[projection.dims[i]], projection.low[i],
                                          projection.high[i], projection.bins);
  }
  return cell;
}

absl::Status ValidateProjection(const StateProjection& projection, int observation_size) {
  const std::string name = absl::StrCat("projection '", projection.name, "'");
  if (projection.name.empty()) return absl::InvalidArgumentError("a projection needs a name");
  const size_t dims = projection.dims.size();
  if (dims < 1 || dims > kMaxDims) {
    return absl::InvalidArgumentError(
        absl::StrCat(name, " needs 1 to ", kMaxDims, " dimensions, got ", dims));
  }
  if (projection.bins < 1 || projection.bins > kMaxBins) {
    return absl::InvalidArgumentError(
        absl::StrCat(name, " needs 1 to ", kMaxBins, " bins, got ", projection.bins));
  }
  if (projection.low.size() != dims || projection.high.size() != dims) {
    return absl::InvalidArgumentError(absl::StrCat(name, " needs a low and a high for each of its ",
                                                   dims, " dimensions"));
  }
  for (size_t i = 0; i < dims; ++i) {
    const int dim = projection.dims[i];
    if (dim < 0 || dim >= observation_size) {
      return absl::InvalidArgumentError(absl::StrCat(
          name, ": dimension ", dim, " is not in the observation (0 to ", observation_size - 1,
          ")"));
    }
    if (std::count(projection.dims.begin(), projection.dims.end(), dim) > 1) {
      return absl::InvalidArgumentError(
          absl::StrCat(name, ": dimension ", dim, " is given twice"));
    }
    const double low = projection.low[i];
    const double high = projection.high[i];
    if (!std::isfinite(low) || !std::isfinite(high) || !(low < high)) {
      return absl::InvalidArgumentError(
          absl::StrCat(name, ": dimension ", dim, " needs finite low < high, got [", low, ", ",
                       high, "]"));
    }
  }
  return absl::OkStatus();
}

}  // namespace dcs::env
