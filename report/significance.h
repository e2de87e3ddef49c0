// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SIGNIFICANCE_H_
#define DCS_REPORT_SIGNIFICANCE_H_

// Whether a condition's runs differ from the baseline's, beyond seed noise, when many
// conditions are compared with one baseline. Companion of report/probability_of_improvement.h,
// whose P(X > Y) + 0.5 P(X = Y) is the Mann-Whitney U statistic of X over |X| |Y|: the test here
// asks whether that probability differs from 0.5.
//  - MannWhitneyTest: the two-sided Mann-Whitney U test, with the normal approximation, the
//    tie correction and the continuity correction (scipy.stats.mannwhitneyu with
//    method="asymptotic", its default for samples this size with ties).
//  - HolmAdjusted: Holm's step-down adjustment of a family of p-values (statsmodels'
//    multipletests method "holm"): a comparison is significant at level alpha when its adjusted
//    p-value is below alpha, and the chance that any true null is rejected stays within alpha.
// Thread-safe (pure functions).

#include <span>
#include <vector>

#include "absl/status/statusor.h"

namespace dcs::report {

struct MannWhitney {
  double u = 0;  // U of x: #{x > y} + 0.5 #{x = y} over all pairs
  double z = 0;  // the corrected normal deviate of max(U_x, U_y); 0 when every value ties
  double p_value = 1;  // two-sided
};

// The test of `x` against `y`. INVALID_ARGUMENT if either is empty or holds a value that is
// not finite.
absl::StatusOr<MannWhitney> MannWhitneyTest(std::span<const double> x, std::span<const double> y);

// The Holm-adjusted p-values of `p_values`, in their order: with p_(1) <= ... <= p_(m) sorted,
// adjusted p_(i) = max over j <= i of min(1, (m - j + 1) p_(j)). INVALID_ARGUMENT for a p-value
// outside [0, 1] or NaN.
absl::StatusOr<std::vector<double>> HolmAdjusted(std::span<const double> p_values);

}  // namespace dcs::report

#endif  // DCS_REPORT_SIGNIFICANCE_H_
