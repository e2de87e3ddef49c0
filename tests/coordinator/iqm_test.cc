// Copyright 2026 The DCS Authors.
#include "coordinator/iqm.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <thread>
#include <vector>

#include "common/random.h"
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

// The definition, computed the slow way: each resample drawn value by value, stratum after
// stratum, from StreamSeed(seed, "bootstrap"), sorted and trimmed; the IQMs sorted, and their
// quantiles by numpy's rule.
ConfidenceInterval DefinitionIqmInterval(const std::vector<std::vector<double>>& strata,
                                         double confidence, int repetitions, uint64_t seed) {
  Random random(StreamSeed(seed, "bootstrap"));
  std::vector<double> estimates;
  for (int r = 0; r < repetitions; ++r) {
    std::vector<double> sample;
    for (const std::vector<double>& stratum : strata) {
      const auto size = static_cast<int64_t>(stratum.size());
      for (int64_t i = 0; i < size; ++i) sample.push_back(stratum[random.Integers(0, size)]);
    }
    estimates.push_back(*InterquartileMean(sample));
  }
  const double tail = (1 - confidence) / 2;
  return {.lo = *Quantile(estimates, tail), .hi = *Quantile(estimates, 1 - tail)};
}

// Values in [0, 1000); with `ties`, whole numbers below 8, so that values repeat.
std::vector<double> RandomValues(Random& random, int size, bool ties) {
  std::vector<double> values;
  for (int i = 0; i < size; ++i) {
    values.push_back(ties ? static_cast<double>(random.Integers(0, 8)) : random.Uniform(0, 1000));
  }
  return values;
}

void ExpectSameInterval(const ConfidenceInterval& actual, const ConfidenceInterval& expected) {
  EXPECT_EQ(actual.lo, expected.lo);
  EXPECT_EQ(actual.hi, expected.hi);
}

TEST(BootstrapTest, SameBitsAsTheDefinition) {
  // Sizes around the fast path's bounds (internal::kMaxLaneValues values, 256-resample blocks),
  // ties and several strata; confidences from 0.01 to 0.99, so that across them the interval
  // reads order statistics all through the sorted IQMs.
  Random random(17);
  const std::vector<std::vector<int>> shapes = {{1},  {2},      {3},       {5},   {8},       {10},
                                                {17}, {10, 10}, {3, 1, 4}, {255}, {200, 56}, {300}};
  for (const std::vector<int>& shape : shapes) {
    for (const bool ties : {false, true}) {
      std::vector<std::vector<double>> strata;
      for (const int size : shape) strata.push_back(RandomValues(random, size, ties));
      const int repetitions = shape.size() == 1 && shape[0] >= 255 ? 300 : 777;
      for (const double confidence : {0.01, 0.2, 0.5, 0.8, 0.9, 0.95, 0.99}) {
        SCOPED_TRACE(testing::Message()
                     << "strata of " << testing::PrintToString(shape) << (ties ? " with ties" : "")
                     << ", confidence " << confidence);
        ExpectSameInterval(*BootstrapIqmInterval(strata, confidence, repetitions, 5),
                           DefinitionIqmInterval(strata, confidence, repetitions, 5));
      }
    }
  }
}

TEST(BootstrapTest, TheReportsDefaultsGiveTheDefinitionsBits) {
  // One cell of a report: 10 seeds, 10,000 resamples at 95% from seed 0.
  Random random(23);
  const std::vector<std::vector<double>> strata = {RandomValues(random, 10, false)};
  ExpectSameInterval(*BootstrapIqmInterval(strata, 0.95, 10'000, 0),
                     DefinitionIqmInterval(strata, 0.95, 10'000, 0));
}

TEST(BootstrapTest, DrawsSharedAcrossCellsAndThreadsChangeNothing) {
  // The process keeps the draws of the last shapes asked for: a cell computed first, again
  // after other shapes evicted its draws, or on another thread gives the same bits.
  Random random(29);
  const std::vector<double> a = RandomValues(random, 10, false);
  const std::vector<double> b = RandomValues(random, 10, false);
  const std::vector<double> nine = RandomValues(random, 9, false);
  const std::vector<double> eight = RandomValues(random, 8, false);
  const ConfidenceInterval first = *BootstrapIqmInterval({a}, 0.95, 2000, 0);
  ASSERT_TRUE(BootstrapIqmInterval({b}, 0.95, 2000, 0).ok());
  ASSERT_TRUE(BootstrapIqmInterval({nine}, 0.95, 2000, 0).ok());
  ASSERT_TRUE(BootstrapIqmInterval({eight}, 0.95, 2000, 0).ok());  // evicts the 10-value draws
  ASSERT_TRUE(BootstrapIqmInterval({a}, 0.95, 2000, 1).ok());
  ExpectSameInterval(*BootstrapIqmInterval({a}, 0.95, 2000, 0), first);
  ConfidenceInterval elsewhere;
  std::thread([&] { elsewhere = *BootstrapIqmInterval({a}, 0.95, 2000, 0); }).join();
  ExpectSameInterval(elsewhere, first);
  ExpectSameInterval(first, DefinitionIqmInterval({a}, 0.95, 2000, 0));
}

TEST(BootstrapDrawsTest, CountsTheDrawsOfEachResampleAndIsSharedUntilEvicted) {
  const size_t sizes[] = {3, 1, 4};
  const internal::BootstrapDraws draws(sizes, 50, 7, "test");
  Random random(StreamSeed(7, "test"));
  for (int r = 0; r < 50; ++r) {
    std::vector<int> counts(8, 0);
    internal::DrawResample(sizes, random, [&](size_t i) { ++counts[i]; });
    for (size_t i = 0; i < counts.size(); ++i) EXPECT_EQ(draws.counts_of(i)[r], counts[i]);
  }
  const auto shared = internal::BootstrapDraws::Shared(sizes, 50, 7, "test");
  EXPECT_EQ(internal::BootstrapDraws::Shared(sizes, 50, 7, "test"), shared);
  EXPECT_NE(internal::BootstrapDraws::Shared(sizes, 50, 8, "test"), shared);
  EXPECT_EQ(internal::BootstrapDraws::Shared(sizes, 50, 7, "test"), shared);
  // Two other draws since: this one is no longer kept.
  ASSERT_NE(internal::BootstrapDraws::Shared(sizes, 50, 8, "test"), nullptr);
  ASSERT_NE(internal::BootstrapDraws::Shared(sizes, 50, 9, "test"), nullptr);
  EXPECT_NE(internal::BootstrapDraws::Shared(sizes, 50, 7, "test"), shared);
}

TEST(PercentileIntervalTest, SelectsWhatSortingWouldRead) {
  // Too few estimates to be sampled and enough, with and without ties, and arranged so that the
  // sample (every 32nd value from the 16th) holds only the largest: some thresholds it sets
  // miss, and the interval is selected among all estimates.
  Random random(31);
  std::vector<std::vector<double>> cases;
  for (const int size : {1, 2, 7, 255, 256, 1000, 10'000}) {
    cases.push_back(RandomValues(random, size, false));
    cases.push_back(RandomValues(random, size, true));
  }
  std::vector<double> misleading = RandomValues(random, 4096, false);
  for (size_t i = 16; i < misleading.size(); i += 32) misleading[i] += 1e6;
  cases.push_back(misleading);
  for (const std::vector<double>& estimates : cases) {
    for (const double confidence : {0.01, 0.5, 0.9, 0.95, 0.99}) {
      SCOPED_TRACE(testing::Message()
                   << estimates.size() << " estimates, confidence " << confidence);
      std::vector<double> work = estimates;
      const ConfidenceInterval interval = internal::PercentileInterval(work, confidence);
      const double tail = (1 - confidence) / 2;
      EXPECT_EQ(interval.lo, *Quantile(estimates, tail));
      EXPECT_EQ(interval.hi, *Quantile(estimates, 1 - tail));
    }
  }
}

TEST(PercentileIntervalTest, ATailThatHoldsOneOrderStatisticOfTwoIsNotUsed) {
  // 256 estimates at 90 %: the 5 % quantile reads ranks 12 and 13. The sample (every 32nd
  // estimate from the 16th: 0 to 7) puts the lower threshold at 4, and 8 more estimates below
  // it make the 13 smallest, ranks 0 to 12: the gathered tail lacks rank 13. Negated, the same
  // for the 95 % quantile and the largest.
  std::vector<double> low;
  for (int i = 0; i < 256; ++i) low.push_back(i % 32 == 16 ? i / 32 : 100 + i);
  for (int i = 0; i < 8; ++i) low[i] = 0.1 * (i + 1);
  std::vector<double> high;
  for (const double estimate : low) high.push_back(-estimate);
  const double tail = (1 - 0.9) / 2;
  for (const std::vector<double>& estimates : {low, high}) {
    std::vector<double> work = estimates;
    const ConfidenceInterval interval = internal::PercentileInterval(work, 0.9);
    EXPECT_EQ(interval.lo, *Quantile(estimates, tail));
    EXPECT_EQ(interval.hi, *Quantile(estimates, 1 - tail));
  }
}

TEST(HighestIqmTest, TheFirstGroupOfTheHighestIqmPassingOverEmptyAndNanGroups) {
  EXPECT_EQ(HighestIqm({}), std::nullopt);
  EXPECT_EQ(HighestIqm({{}, {std::nan("")}}), std::nullopt);
  // IQMs: 15, none, 21 (of 12 and 30), 21 again, and a NaN group.
  const std::optional<HighestIqmGroup> highest =
      HighestIqm({{10, 20}, {}, {30, 12}, {21}, {std::nan(""), 99}});
  ASSERT_TRUE(highest.has_value());
  EXPECT_EQ(highest->index, 2u);
  EXPECT_EQ(highest->iqm, 21);
}

}  // namespace
}  // namespace dcs::coordinator
