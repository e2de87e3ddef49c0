// Copyright 2026 The DCS Authors.
#include "coordinator/iqm.h"

#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

TEST(IqmTest, TrimsAQuarterFromEachEndAsScipyTrimMean) {
  // 10 seeds: the middle 6. scipy.stats.trim_mean(range(1, 11), 0.25) == 5.5.
  const std::vector<double> ten = {10, 1, 9, 2, 8, 3, 7, 4, 6, 5};
  EXPECT_DOUBLE_EQ(*InterquartileMean(ten), 5.5);
  // 5 seeds: the middle 3, so one outlier does not move it.
  const std::vector<double> five = {1, 2, 3, 4, 1000};
  EXPECT_DOUBLE_EQ(*InterquartileMean(five), 3.0);
  // 8 seeds: the middle 4.
  const std::vector<double> eight = {0, 0, 10, 20, 30, 40, 100, 100};
  EXPECT_DOUBLE_EQ(*InterquartileMean(eight), 25.0);
  // Fewer than 4: nothing is trimmed.
  const std::vector<double> three = {1, 2, 6};
  EXPECT_DOUBLE_EQ(*InterquartileMean(three), 3.0);
}

TEST(IqmTest, QuartilesInterpolateLinearlyAsNumpy) {
  const std::vector<double> ten = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  // numpy.percentile(range(1, 11), [25, 75]) == [3.25, 7.75].
  const IqmSummary summary = *SummarizeIqm(ten);
  EXPECT_DOUBLE_EQ(summary.iqm, 5.5);
  EXPECT_DOUBLE_EQ(summary.q1, 3.25);
  EXPECT_DOUBLE_EQ(summary.q3, 7.75);
  EXPECT_DOUBLE_EQ(*Quantile(ten, 0), 1);
  EXPECT_DOUBLE_EQ(*Quantile(ten, 1), 10);
  const std::vector<double> one = {42};
  EXPECT_DOUBLE_EQ(*Quantile(one, 0.25), 42);
}

TEST(IqmTest, RejectsEmptyAndNanAndBadQuantiles) {
  EXPECT_EQ(InterquartileMean({}).status().code(), absl::StatusCode::kInvalidArgument);
  const std::vector<double> nan = {1, std::nan("")};
  EXPECT_EQ(SummarizeIqm(nan).status().code(), absl::StatusCode::kInvalidArgument);
  const std::vector<double> ok = {1, 2};
  EXPECT_EQ(Quantile(ok, 1.5).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(BootstrapTest, IntervalHoldsTheEstimateAndNarrowsWithMoreData) {
  std::vector<double> small;
  std::vector<double> large;
  for (int i = 0; i < 10; ++i) small.push_back(i % 5 * 10.0);
  for (int i = 0; i < 200; ++i) large.push_back(i % 5 * 10.0);
  const double estimate = *InterquartileMean(small);
  const ConfidenceInterval narrow_data = *BootstrapIqmInterval({small}, 0.95, 2000, 1);
  const ConfidenceInterval wide_data = *BootstrapIqmInterval({large}, 0.95, 2000, 1);
  EXPECT_LE(narrow_data.lo, estimate);
  EXPECT_GE(narrow_data.hi, estimate);
  EXPECT_LT(wide_data.hi - wide_data.lo, narrow_data.hi - narrow_data.lo);
  // Same seed, same interval; constant data, a point interval.
  const ConfidenceInterval again = *BootstrapIqmInterval({small}, 0.95, 2000, 1);
  EXPECT_EQ(again.lo, narrow_data.lo);
  EXPECT_EQ(again.hi, narrow_data.hi);
  const ConfidenceInterval point = *BootstrapIqmInterval({{7, 7, 7}, {7, 7}}, 0.9, 100, 3);
  EXPECT_EQ(point.lo, 7);
  EXPECT_EQ(point.hi, 7);
}

TEST(BootstrapTest, ResamplesWithinStrata) {
  // Two strata far apart: every resample keeps 3 values from each, so the IQM of the 6 (the
  // middle 4: the two largest of the low stratum and the two smallest of the high one) is in
  // [(0 + 0 + 100 + 100) / 4, (2 + 2 + 102 + 102) / 4] = [50, 52] whatever is drawn. A
  // bootstrap that mixed the strata could go below 50.
  const ConfidenceInterval interval = *BootstrapIqmInterval({{0, 1, 2}, {100, 101, 102}}, 0.99,
                                                            500, 5);
  EXPECT_GE(interval.lo, 50.0);
  EXPECT_LE(interval.hi, 52.0);
  EXPECT_EQ(BootstrapIqmInterval({{1}, {}}, 0.9, 10, 1).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(BootstrapIqmInterval({{1}}, 1.0, 10, 1).status().code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::coordinator
