// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_CORRELATION_H_
#define DCS_COORDINATOR_CORRELATION_H_

// Pearson's correlation with its two-sided p-value, as the paper relates coverage to score
// (the paper's Appendix D: r = 0.21, p = 0.003): r = cov(x, y) / (sd(x) sd(y)), and
//   p = P(|T| >= |t|),  t = r sqrt((n - 2) / (1 - r^2)),  T ~ Student's t with n - 2 degrees of
// freedom (Boost.Math), which is scipy.stats.pearsonr's p-value. Thread-safe (pure function).

#include <span>

#include "absl/status/statusor.h"

namespace dcs::report {

struct Correlation {
  double r = 0;
  double p_value = 1;
  int n = 0;
};

// The correlation of the pairs (x[i], y[i]). INVALID_ARGUMENT for lengths that differ, fewer
// than three pairs, a value that is not finite, or x or y constant (r is undefined).
absl::StatusOr<Correlation> PearsonCorrelation(std::span<const double> x,
                                               std::span<const double> y);

}  // namespace dcs::report

#endif  // DCS_COORDINATOR_CORRELATION_H_
