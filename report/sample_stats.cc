// Copyright 2026 The DCS Authors.
#include "report/sample_stats.h"

#include <cmath>

namespace dcs::report {

double Mean(std::span<const double> values) {
  double sum = 0;
  for (double value : values) sum += value;
  return sum / static_cast<double>(values.size());
}

double StandardError(std::span<const double> values) {
  const size_t n = values.size();
  if (n < 2) return 0;
  const double mean = Mean(values);
  double squares = 0;
  for (double value : values) squares += (value - mean) * (value - mean);
  return std::sqrt(squares / static_cast<double>(n - 1) / static_cast<double>(n));
}

}  // namespace dcs::report
