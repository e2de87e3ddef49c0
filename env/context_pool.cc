// Copyright 2026 The DCS Authors.
#include "env/context_pool.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace dcs::env {

std::vector<double> MidpointInsertion(double lo, double hi, int levels) {
  if (levels == 0) return {0.5 * (lo + hi)};
  std::vector<double> values = {lo, 0.5 * (lo + hi), hi};
  for (int level = 2; level <= levels; ++level) {
    std::vector<double> inserted;
    inserted.reserve(2 * values.size() - 1);
    for (size_t i = 0; i + 1 < values.size(); ++i) {
      inserted.push_back(values[i]);
      inserted.push_back(0.5 * (values[i] + values[i + 1]));
    }
    inserted.push_back(values.back());
    values = std::move(inserted);
  }
  return values;
}

absl::StatusOr<ContextPool> ContextPool::OfSize(double lo, double hi, int size) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
    return absl::InvalidArgumentError(
        absl::StrCat("a pool's range must be finite with lo <= hi, got [", lo, ", ", hi, "]"));
  }
  if (size < 1 || size > 10000) {
    return absl::InvalidArgumentError(
        absl::StrCat("pool size must be in [1, 10000], got ", size));
  }
  // Sizes 1 and 2^j + 1 are the paper's midpoint insertion.
  for (int levels = 0; levels <= 14; ++levels) {
    const int level_size = levels == 0 ? 1 : (1 << levels) + 1;
    if (level_size == size) return ContextPool(MidpointInsertion(lo, hi, levels));
  }
  std::vector<double> values(size);
  for (int i = 0; i < size; ++i) {
    values[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(size - 1);
  }
  return ContextPool(std::move(values));
}

absl::StatusOr<ContextPool> ContextPool::OfValues(std::vector<double> values) {
  if (values.empty()) return absl::InvalidArgumentError("a pool needs at least one value");
  for (double value : values) {
    if (!std::isfinite(value)) {
      return absl::InvalidArgumentError(absl::StrCat("pool values must be finite, got ", value));
    }
  }
  return ContextPool(std::move(values));
}

double ContextPool::Select(Selection selection, uint64_t episode, uint64_t slot,
                           Random& random) const {
  const uint64_t size = values_.size();
  if (selection == Selection::kRoundRobin) return values_[(episode + slot) % size];
  return values_[random.Integers(0, static_cast<int64_t>(size))];
}

}  // namespace dcs::env
