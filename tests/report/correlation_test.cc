// Copyright 2026 The DCS Authors.
#include "report/correlation.h"

#include <limits>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;

TEST(CorrelationTest, PearsonsRAndItsTwoSidedPValue) {
  // r = sqrt(0.6); with 3 degrees of freedom Student's t has a closed-form CDF, which gives
  // p = 0.12402706265755459 (scipy.stats.pearsonr's value for these pairs).
  const std::vector<double> x = {1, 2, 3, 4, 5};
  const std::vector<double> y = {2, 4, 5, 4, 5};
  absl::StatusOr<Correlation> c = PearsonCorrelation(x, y);
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_NEAR(c->r, 0.7745966692414834, 1e-15);
  EXPECT_NEAR(c->p_value, 0.12402706265755459, 1e-12);
  EXPECT_EQ(c->n, 5);
  // Negated: the same p, the opposite sign.
  const std::vector<double> minus_y = {-2, -4, -5, -4, -5};
  absl::StatusOr<Correlation> negative = PearsonCorrelation(x, minus_y);
  ASSERT_TRUE(negative.ok());
  EXPECT_NEAR(negative->r, -c->r, 1e-15);
  EXPECT_NEAR(negative->p_value, c->p_value, 1e-12);
}

TEST(CorrelationTest, ALineIsPerfectlyCorrelated) {
  absl::StatusOr<Correlation> c =
      PearsonCorrelation(std::vector<double>{1, 2, 3}, std::vector<double>{10, 20, 30});
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->r, 1);
  EXPECT_EQ(c->p_value, 0);
}

TEST(CorrelationTest, RefusesWhatHasNoCorrelation) {
  const std::vector<double> three = {1, 2, 3};
  EXPECT_THAT(PearsonCorrelation(three, std::vector<double>{1, 2}).status().message(),
              HasSubstr("3 x values, 2 y"));
  EXPECT_THAT(PearsonCorrelation(std::vector<double>{1, 2}, std::vector<double>{1, 2})
                  .status()
                  .message(),
              HasSubstr("at least three pairs"));
  EXPECT_THAT(PearsonCorrelation(three, std::vector<double>{4, 4, 4}).status().message(),
              HasSubstr("y is constant"));
  EXPECT_THAT(PearsonCorrelation(three, std::vector<double>{
                                            1, std::numeric_limits<double>::quiet_NaN(), 2})
                  .status()
                  .message(),
              HasSubstr("not finite"));
}

}  // namespace
}  // namespace dcs::report
