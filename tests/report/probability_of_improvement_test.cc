// Copyright 2026 The DCS Authors.
#include "report/probability_of_improvement.h"

#include <cmath>
#include <utility>
#include <vector>

#include "common/random.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

TEST(ProbabilityOfImprovementTest, CountsWinsAndHalfTiesOverAllPairs) {
  // {1, 2, 3} over {2, 2, 2}: 1 loses its 3 pairs, 2 ties its 3 (0.5 each), 3 wins its 3:
  // (0 + 1.5 + 3) / 9 = 0.5.
  const std::vector<double> x = {1, 2, 3};
  const std::vector<double> y = {2, 2, 2};
  EXPECT_DOUBLE_EQ(*ProbabilityOfImprovement(x, y), 0.5);
  // {3, 4} over {1, 3, 5}: 3 > 1, 3 = 3, 3 < 5, 4 > 1, 4 > 3, 4 < 5: 3.5 / 6.
  const std::vector<double> a = {3, 4};
  const std::vector<double> b = {1, 3, 5};
  EXPECT_DOUBLE_EQ(*ProbabilityOfImprovement(a, b), 3.5 / 6);
  EXPECT_DOUBLE_EQ(*ProbabilityOfImprovement(b, a), 2.5 / 6);  // P(X>Y) + P(Y>X) + P(=) = 1
  const std::vector<double> high = {5, 6};
  const std::vector<double> low = {1, 2};
  EXPECT_EQ(*ProbabilityOfImprovement(high, low), 1);
  EXPECT_EQ(*ProbabilityOfImprovement(low, high), 0);
  EXPECT_EQ(*ProbabilityOfImprovement(x, x), 0.5);
}

TEST(ProbabilityOfImprovementTest, RejectsEmptyAndNan) {
  const std::vector<double> ok = {1, 2};
  const std::vector<double> nan = {1, std::nan("")};
  EXPECT_EQ(ProbabilityOfImprovement({}, ok).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ProbabilityOfImprovement(ok, nan).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(BootstrapImprovementInterval(ok, ok, 1.0, 10, 0).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(BootstrapImprovementInterval(ok, ok, 0.95, 0, 0).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(BootstrapImprovementInterval(ok, {}, 0.95, 10, 0).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(BootstrapImprovementTest, OneRepetitionIsTheImprovementOfOneResampleOfEachSide) {
  // The documented stream and order: X's runs, then Y's, from StreamSeed(seed, "improvement").
  const std::vector<double> x = {1, 4, 6, 9};
  const std::vector<double> y = {2, 5, 7};
  Random random(StreamSeed(11, "improvement"));
  std::vector<double> x_sample;
  std::vector<double> y_sample;
  for (size_t i = 0; i < x.size(); ++i) x_sample.push_back(x[random.Integers(0, 4)]);
  for (size_t i = 0; i < y.size(); ++i) y_sample.push_back(y[random.Integers(0, 3)]);
  const double expected = *ProbabilityOfImprovement(x_sample, y_sample);
  const coordinator::ConfidenceInterval interval = *BootstrapImprovementInterval(x, y, 0.95, 1, 11);
  EXPECT_EQ(interval.lo, expected);
  EXPECT_EQ(interval.hi, expected);
}

TEST(BootstrapImprovementTest, IntervalHoldsTheEstimateAndIsDeterministic) {
  const std::vector<double> x = {3, 6, 9, 2, 5, 8, 1, 4, 7, 10};
  const std::vector<double> y = {5, 1, 4, 2, 8, 9, 3, 7, 6, 0};
  const double estimate = *ProbabilityOfImprovement(x, y);
  const coordinator::ConfidenceInterval interval =
      *BootstrapImprovementInterval(x, y, 0.95, 2000, 0);
  EXPECT_LT(interval.lo, estimate);
  EXPECT_GT(interval.hi, estimate);
  EXPECT_GE(interval.lo, 0);
  EXPECT_LE(interval.hi, 1);
  const coordinator::ConfidenceInterval again = *BootstrapImprovementInterval(x, y, 0.95, 2000, 0);
  EXPECT_EQ(again.lo, interval.lo);
  EXPECT_EQ(again.hi, interval.hi);
  const coordinator::ConfidenceInterval other = *BootstrapImprovementInterval(x, y, 0.95, 2000, 1);
  EXPECT_TRUE(other.lo != interval.lo || other.hi != interval.hi);
  // A narrower confidence gives a narrower interval from the same resamples.
  const coordinator::ConfidenceInterval narrow = *BootstrapImprovementInterval(x, y, 0.5, 2000, 0);
  EXPECT_GE(narrow.lo, interval.lo);
  EXPECT_LE(narrow.hi, interval.hi);
  EXPECT_LT(narrow.hi - narrow.lo, interval.hi - interval.lo);
}

TEST(BootstrapImprovementTest, SeparatedSamplesGiveAPointInterval) {
  const std::vector<double> high = {10, 11, 12};
  const std::vector<double> low = {1, 2, 3};
  const coordinator::ConfidenceInterval interval =
      *BootstrapImprovementInterval(high, low, 0.95, 100, 0);
  EXPECT_EQ(interval.lo, 1);
  EXPECT_EQ(interval.hi, 1);
}

// The definition, computed the slow way: each repetition draws X's runs and then Y's, value by
// value, from StreamSeed(seed, "improvement") and counts all pairs of the resamples (the
// O(|x| |y|) ProbabilityOfImprovement); the estimates sorted, their quantiles by numpy's rule.
coordinator::ConfidenceInterval DefinitionImprovementInterval(const std::vector<double>& x,
                                                              const std::vector<double>& y,
                                                              double confidence, int repetitions,
                                                              uint64_t seed) {
  Random random(StreamSeed(seed, "improvement"));
  std::vector<double> estimates;
  for (int r = 0; r < repetitions; ++r) {
    std::vector<double> x_sample;
    std::vector<double> y_sample;
    const auto x_size = static_cast<int64_t>(x.size());
    const auto y_size = static_cast<int64_t>(y.size());
    for (int64_t i = 0; i < x_size; ++i) x_sample.push_back(x[random.Integers(0, x_size)]);
    for (int64_t i = 0; i < y_size; ++i) y_sample.push_back(y[random.Integers(0, y_size)]);
    estimates.push_back(*ProbabilityOfImprovement(x_sample, y_sample));
  }
  const double tail = (1 - confidence) / 2;
  return {.lo = *coordinator::Quantile(estimates, tail),
          .hi = *coordinator::Quantile(estimates, 1 - tail)};
}

// `size` runs; with `ties`, whole numbers below 6, so that runs of X and Y tie often.
std::vector<double> RandomRuns(Random& random, int size, bool ties) {
  std::vector<double> runs;
  for (int i = 0; i < size; ++i) {
    runs.push_back(ties ? static_cast<double>(random.Integers(0, 6)) : random.Uniform(0, 1));
  }
  return runs;
}

TEST(BootstrapImprovementTest, FastResamplesCountWhatAllPairsCount) {
  // The bootstrap works from ranks and drawn counts, never the pairs; it must give the bits of
  // counting every pair of every resample. Sizes around the fast path's bound
  // (internal::kMaxLaneValues runs a side) and its 256-resample blocks, with and without ties;
  // confidences from 0.01 to 0.99 read order statistics all through the sorted estimates.
  Random random(13);
  const std::vector<std::pair<int, int>> sizes = {{1, 1},  {1, 5},  {4, 3},   {10, 10},
                                                  {7, 12}, {30, 2}, {255, 9}, {256, 3}};
  for (const auto& [x_size, y_size] : sizes) {
    for (const bool ties : {false, true}) {
      const std::vector<double> x = RandomRuns(random, x_size, ties);
      const std::vector<double> y = RandomRuns(random, y_size, ties);
      const int repetitions = x_size >= 255 ? 300 : 777;
      for (const double confidence : {0.01, 0.2, 0.5, 0.8, 0.9, 0.95, 0.99}) {
        SCOPED_TRACE(testing::Message()
                     << x_size << " x " << y_size << " runs" << (ties ? " with ties" : "")
                     << ", confidence " << confidence);
        const coordinator::ConfidenceInterval fast =
            *BootstrapImprovementInterval(x, y, confidence, repetitions, 3);
        const coordinator::ConfidenceInterval definition =
            DefinitionImprovementInterval(x, y, confidence, repetitions, 3);
        EXPECT_EQ(fast.lo, definition.lo);
        EXPECT_EQ(fast.hi, definition.hi);
      }
    }
  }
}

TEST(BootstrapImprovementTest, TheReportsDefaultsGiveTheDefinitionsBits) {
  // One cell of a report against its baseline: 10 seeds each, 10,000 resamples at 95%, seed 0.
  Random random(19);
  const std::vector<double> x = RandomRuns(random, 10, false);
  const std::vector<double> y = RandomRuns(random, 10, false);
  const coordinator::ConfidenceInterval fast = *BootstrapImprovementInterval(x, y, 0.95, 10'000, 0);
  const coordinator::ConfidenceInterval definition =
      DefinitionImprovementInterval(x, y, 0.95, 10'000, 0);
  EXPECT_EQ(fast.lo, definition.lo);
  EXPECT_EQ(fast.hi, definition.hi);
}

}  // namespace
}  // namespace dcs::report
