// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_PROBABILITY_OF_IMPROVEMENT_H_
#define DCS_REPORT_PROBABILITY_OF_IMPROVEMENT_H_

// rliable's probability of improvement (Agarwal et al., 2021) of one algorithm X over another Y
// on one task: P(X > Y) + 0.5 P(X = Y) for a run of each drawn at random, counted over all
// pairs of runs (the Mann-Whitney U statistic of X divided by |X| |Y|), and its percentile
// bootstrap interval. Companion of coordinator/iqm.h. Thread-safe (pure functions).

#include <cstdint>
#include <span>

#include "absl/status/statusor.h"
#include "coordinator/iqm.h"

namespace dcs::report {

// (#{x > y} + 0.5 #{x = y}) / (|x| |y|) over all pairs (x, y): 1 when every run of `x` beats
// every run of `y`, 0.5 for identical samples. INVALID_ARGUMENT if either is empty or holds a
// NaN.
absl::StatusOr<double> ProbabilityOfImprovement(std::span<const double> x,
                                                std::span<const double> y);

// A percentile bootstrap interval for ProbabilityOfImprovement(x, y), as rliable's
// StratifiedIndependentBootstrap draws it for one task: each repetition resamples `x` and then
// `y` with replacement, independently (internal::DrawResample with the strata x, y), from
// StreamSeed(seed, "improvement"); the interval is as BootstrapIqmInterval's. A resample costs
// O(|x| + |y|), not |x| |y| comparisons: from each run's rank among the other side's runs and
// how often it was drawn. Up to internal::kMaxLaneValues runs a side, calls with equal sizes,
// repetitions and seed share their draws, as there. `confidence` is e.g. 0.95.
// INVALID_ARGUMENT as ProbabilityOfImprovement, or for confidence outside (0, 1) or
// repetitions < 1.
absl::StatusOr<coordinator::ConfidenceInterval> BootstrapImprovementInterval(
    std::span<const double> x, std::span<const double> y, double confidence, int repetitions,
    uint64_t seed);

}  // namespace dcs::report

#endif  // DCS_REPORT_PROBABILITY_OF_IMPROVEMENT_H_
