// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SAMPLE_STATS_H_
#define DCS_REPORT_SAMPLE_STATS_H_

// The mean of a sample and its standard error, as the tests and reports of this folder use them
// (report/anova.h, report/correlation.h, report/coverage_report.h). Thread-safe
// (pure functions).

#include <span>

namespace dcs::report {

// The arithmetic mean, summed in order. REQUIRES: `values` non-empty.
double Mean(std::span<const double> values);

// The standard error of the mean: the sample standard deviation (n - 1 in the denominator) over
// sqrt(n); 0 for fewer than two values.
double StandardError(std::span<const double> values);

}  // namespace dcs::report

#endif  // DCS_REPORT_SAMPLE_STATS_H_
