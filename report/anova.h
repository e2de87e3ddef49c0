// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_ANOVA_H_
#define DCS_COORDINATOR_ANOVA_H_

// One-way analysis of variance, as the paper tests whether conditions differ in coverage
// (docs/reference.md, "Coverage"; the paper's Appendix D): do k groups of N values in all share one
// mean?
//   F = (SSB / (k - 1)) / (SSW / (N - k)),  p = P(F(k - 1, N - k) > F),
// SSB = sum over groups of n_i (mean_i - mean)^2, SSW = sum of (x - mean_i)^2 within groups;
// scipy.stats.f_oneway's statistic and p-value. Thread-safe (pure function).

#include <vector>

#include "absl/status/statusor.h"

namespace dcs::report {

struct AnovaResult {
  double f = 0;        // +inf when every group is constant but their means differ
  int df_between = 0;  // k - 1
  int df_within = 0;   // N - k
  double p_value = 1;  // 0 when f is +inf
};

// The one-way ANOVA of `groups`. INVALID_ARGUMENT for fewer than two groups, an empty group, no
// group of two or more values (N - k = 0: no variance within groups to compare with), a NaN or
// infinite value, or values all equal (F is 0/0).
absl::StatusOr<AnovaResult> OneWayAnova(const std::vector<std::vector<double>>& groups);

}  // namespace dcs::report

#endif  // DCS_COORDINATOR_ANOVA_H_
