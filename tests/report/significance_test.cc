// Copyright 2026 The DCS Authors.
#include "report/significance.h"

#include <limits>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/probability_of_improvement.h"

namespace dcs::report {
namespace {

using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(SignificanceTest, MannWhitneyAsScipysAsymptoticTest) {
  // scipy.stats.mannwhitneyu's documented example (its method="asymptotic"): U = 17,
  // p = 0.11134688653314041.
  const std::vector<double> males = {19, 22, 16, 29, 24};
  const std::vector<double> females = {20, 11, 17, 12};
  absl::StatusOr<MannWhitney> test = MannWhitneyTest(males, females);
  ASSERT_TRUE(test.ok()) << test.status();
  EXPECT_EQ(test->u, 17);
  EXPECT_NEAR(test->p_value, 0.11134688653314041, 1e-14);
  // Two-sided: the sides swapped give the same p and the other U.
  absl::StatusOr<MannWhitney> swapped = MannWhitneyTest(females, males);
  ASSERT_TRUE(swapped.ok());
  EXPECT_EQ(swapped->u, 3);
  EXPECT_NEAR(swapped->p_value, test->p_value, 1e-15);
}

TEST(SignificanceTest, TiesShareTheirRanksAndNarrowTheVariance) {
  // x's ranks among {1, 2, 2, 2, 3, 3, 3, 3, 4, 4} are 1, 3, 3, 6.5, 6.5, 6.5: U = 26.5 - 21
  // = 5.5. The tie groups of 3, 4 and 2 values take (24 + 60 + 6) / (10 * 9) = 1 from
  // n + 1 = 11 in the variance: sd = sqrt(24 / 12 * 10), z = (24 - 5.5 - 12 - 0.5) / sd,
  // p = erfc(z / sqrt(2)).
  const std::vector<double> x = {1, 2, 2, 3, 3, 3};
  const std::vector<double> y = {2, 3, 4, 4};
  absl::StatusOr<MannWhitney> test = MannWhitneyTest(x, y);
  ASSERT_TRUE(test.ok()) << test.status();
  EXPECT_EQ(test->u, 5.5);
  EXPECT_NEAR(test->z, 1.3416407864998738, 1e-14);
  EXPECT_NEAR(test->p_value, 0.17971249487899985, 1e-14);
  // U over |x| |y| is the probability of improvement.
  absl::StatusOr<double> probability = ProbabilityOfImprovement(x, y);
  ASSERT_TRUE(probability.ok());
  EXPECT_EQ(test->u / 24, *probability);
}

TEST(SignificanceTest, SeparatedSamplesAreSignificantAndIdenticalOnesAreNot) {
  absl::StatusOr<MannWhitney> apart =
      MannWhitneyTest(std::vector<double>{1, 2, 3, 4, 5}, std::vector<double>{6, 7, 8, 9, 10});
  ASSERT_TRUE(apart.ok());
  EXPECT_EQ(apart->u, 0);
  EXPECT_NEAR(apart->p_value, 0.012185780355344818, 1e-14);
  absl::StatusOr<MannWhitney> alike =
      MannWhitneyTest(std::vector<double>{4, 4, 4}, std::vector<double>{4, 4});
  ASSERT_TRUE(alike.ok());
  EXPECT_EQ(alike->u, 3);
  EXPECT_EQ(alike->z, 0);
  EXPECT_EQ(alike->p_value, 1);
}

TEST(SignificanceTest, MannWhitneyRefusesWhatItCannotRank) {
  const std::vector<double> some = {1, 2};
  EXPECT_THAT(MannWhitneyTest(some, std::vector<double>{}).status().message(),
              HasSubstr("runs on both sides, got 2 and 0"));
  EXPECT_THAT(
      MannWhitneyTest(some, std::vector<double>{std::numeric_limits<double>::quiet_NaN()})
          .status()
          .message(),
      HasSubstr("finite values, got nan"));
}

TEST(SignificanceTest, HolmStepsDownAndKeepsTheOrder) {
  // Sorted 0.005, 0.01, 0.03, 0.04 times 4, 3, 2, 1: 0.02, 0.03, 0.06, 0.04 -> running maximum
  // 0.02, 0.03, 0.06, 0.06; given back in the input's order.
  absl::StatusOr<std::vector<double>> adjusted =
      HolmAdjusted(std::vector<double>{0.01, 0.04, 0.03, 0.005});
  ASSERT_TRUE(adjusted.ok()) << adjusted.status();
  EXPECT_THAT(*adjusted, ElementsAre(DoubleNear(0.03, 1e-15), DoubleNear(0.06, 1e-15),
                                     DoubleNear(0.06, 1e-15), DoubleNear(0.02, 1e-15)));
  // Capped at 1; one comparison is left as it is; none gives none.
  EXPECT_THAT(*HolmAdjusted(std::vector<double>{0.5, 0.6}), ElementsAre(1, 1));
  EXPECT_THAT(*HolmAdjusted(std::vector<double>{0.2}), ElementsAre(0.2));
  EXPECT_TRUE(HolmAdjusted({})->empty());
  EXPECT_THAT(HolmAdjusted(std::vector<double>{0.1, 1.5}).status().message(),
              HasSubstr("in [0, 1], got 1.5"));
}

}  // namespace
}  // namespace dcs::report
