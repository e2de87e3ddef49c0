// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_IQM_H_
#define DCS_COORDINATOR_IQM_H_

// The paper's across-seed statistics (spec/schedules.md §9.3), after Agarwal et al. (2021):
// the interquartile mean (IQM) with the first and third quartiles, "IQM [Q1, Q3]", and a
// stratified bootstrap confidence interval for the IQM. Thread-safe (pure functions).

#include <cstdint>
#include <span>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/random.h"

namespace dcs::coordinator {

// The 25% trimmed mean, as rliable and scipy.stats.trim_mean(x, 0.25) compute it: sort, drop
// floor(n / 4) values from each end, average the rest (10 seeds: the middle 6; 8: the middle
// 4; 5: the middle 3). INVALID_ARGUMENT if `values` is empty or holds a NaN.
absl::StatusOr<double> InterquartileMean(std::span<const double> values);

// The q-th quantile (0 <= q <= 1) with linear interpolation between order statistics, numpy's
// default: position (n - 1) * q. INVALID_ARGUMENT as above, or for q outside [0, 1].
absl::StatusOr<double> Quantile(std::span<const double> values, double q);

struct IqmSummary {
  double iqm = 0;
  double q1 = 0;
  double q3 = 0;
};

// IQM [Q1, Q3] of `values`. Errors as InterquartileMean.
absl::StatusOr<IqmSummary> SummarizeIqm(std::span<const double> values);

struct ConfidenceInterval {
  double lo = 0;
  double hi = 0;
};

// A percentile bootstrap interval (the confidence's two tails of `repetitions` estimates, by
// Quantile's rule): each estimate is `estimate(random)`, computed on a resample the estimator
// draws from `random` (e.g. with AppendResample), which is seeded by StreamSeed(seed, stream).
// INVALID_ARGUMENT for confidence outside (0, 1) or repetitions < 1.
absl::StatusOr<ConfidenceInterval> PercentileBootstrap(
    double confidence, int repetitions, uint64_t seed, absl::string_view stream,
    absl::FunctionRef<double(Random& random)> estimate);

// Appends a resample of `from` (as many values, drawn with replacement) to `to`.
void AppendResample(std::span<const double> from, Random& random, std::vector<double>& to);

// A percentile bootstrap interval for the IQM of all values together, resampling with
// replacement within each stratum (rliable's StratifiedBootstrap: a stratum is a task, its
// values the runs on it; one stratum is a plain bootstrap over seeds). `confidence` is e.g.
// 0.95; `repetitions` bootstrap samples drawn from StreamSeed(seed, "bootstrap").
// INVALID_ARGUMENT for an empty stratum, NaN, confidence outside (0, 1) or repetitions < 1.
absl::StatusOr<ConfidenceInterval> BootstrapIqmInterval(
    const std::vector<std::vector<double>>& strata, double confidence, int repetitions,
    uint64_t seed);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_IQM_H_
