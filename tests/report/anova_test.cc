// Copyright 2026 The DCS Authors.
#include "report/anova.h"

#include <cmath>
#include <limits>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

TEST(AnovaTest, MatchesScipyFOnewayDocumentationExample) {
  // scipy.stats.f_oneway's documentation example (McDonald, Handbook of Biological Statistics,
  // "One-way ANOVA": the length of the anterior adductor muscle scar of Mytilus trossulus,
  // divided by total length, at five locations). The documentation prints
  // F_onewayResult(statistic=7.121019471642447, pvalue=0.0002812242314534544);
  // the handbook gives F = 7.12 with 4 and 34 degrees of freedom, P = 2.8e-4.
  const std::vector<std::vector<double>> groups = {
      // Tillamook
      {0.0571, 0.0813, 0.0831, 0.0976, 0.0817, 0.0859, 0.0735, 0.0659, 0.0923, 0.0836},
      {0.0873, 0.0662, 0.0672, 0.0819, 0.0749, 0.0649, 0.0835, 0.0725},  // Newport
      {0.0974, 0.1352, 0.0817, 0.1016, 0.0968, 0.1064, 0.105},           // Petersburg
      {0.1033, 0.0915, 0.0781, 0.0685, 0.0677, 0.0697, 0.0764, 0.0689},  // Magadan
      {0.0703, 0.1026, 0.0956, 0.0973, 0.1039, 0.1045}};                 // Tvarminne
  const absl::StatusOr<AnovaResult> result = OneWayAnova(groups);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->df_between, 4);
  EXPECT_EQ(result->df_within, 34);
  EXPECT_NEAR(result->f, 7.121019471642447, 7.121019471642447 * 1e-12);
  EXPECT_NEAR(result->p_value, 0.0002812242314534544, 0.0002812242314534544 * 1e-9);
}

TEST(AnovaTest, MatchesAHandComputedTwoGroupExample) {
  // {1, 2, 3} and {4, 5, 6}: means 2 and 5, grand mean 3.5; SSB = 3 * 1.5^2 * 2 = 13.5, SSW =
  // 2 + 2 = 4, so F = (13.5 / 1) / (4 / 4) = 13.5 with (1, 4) degrees of freedom. Its tail is
  // the regularised incomplete beta I_x(2, 1/2) at x = 4 / (4 + F): with y = 1 - x = F / (4 + F)
  // = 27/35, I_x(2, 1/2) = 1 - sqrt(y) (3 - y) / 2 = 0.021311641128756...
  const absl::StatusOr<AnovaResult> result = OneWayAnova({{1, 2, 3}, {4, 5, 6}});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_DOUBLE_EQ(result->f, 13.5);
  EXPECT_EQ(result->df_between, 1);
  EXPECT_EQ(result->df_within, 4);
  const double y = 27.0 / 35.0;
  EXPECT_NEAR(result->p_value, 1 - std::sqrt(y) * (3 - y) / 2, 1e-14);
}

TEST(AnovaTest, EqualMeansGiveFZeroAndPOne) {
  // Means 2 and 2: SSB = 0, SSW = 2.
  const absl::StatusOr<AnovaResult> result = OneWayAnova({{1, 3}, {2, 2}, {0, 4}});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->f, 0);
  EXPECT_DOUBLE_EQ(result->p_value, 1);
}

TEST(AnovaTest, GroupsOfOneValueCountWhenAnotherGroupHasVariance) {
  // {5} and {1, 3}: grand mean 3; SSB = 1 * 2^2 + 2 * 1^2 = 6, SSW = 2; F = 6 / (2 / 1) = 3.
  const absl::StatusOr<AnovaResult> result = OneWayAnova({{5}, {1, 3}});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_DOUBLE_EQ(result->f, 3);
  EXPECT_EQ(result->df_within, 1);
}

TEST(AnovaTest, ConstantGroupsWithDifferentMeansGiveAnInfiniteF) {
  const absl::StatusOr<AnovaResult> result = OneWayAnova({{1, 1}, {2, 2}});
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(result->f, std::numeric_limits<double>::infinity());
  EXPECT_EQ(result->p_value, 0);
}

TEST(AnovaTest, RefusesWhatHasNoAnswer) {
  const auto code = [](const std::vector<std::vector<double>>& groups) {
    return OneWayAnova(groups).status().code();
  };
  constexpr absl::StatusCode kInvalid = absl::StatusCode::kInvalidArgument;
  EXPECT_EQ(code({}), kInvalid);
  EXPECT_EQ(code({{1, 2, 3}}), kInvalid);               // one group
  EXPECT_EQ(code({{1, 2}, {}}), kInvalid);              // an empty group
  EXPECT_EQ(code({{1}, {2}, {3}}), kInvalid);           // N - k = 0
  EXPECT_EQ(code({{1, 2}, {3, std::nan("")}}), kInvalid);
  EXPECT_EQ(code({{1, 2}, {3, std::numeric_limits<double>::infinity()}}), kInvalid);
  EXPECT_EQ(code({{4, 4}, {4, 4, 4}}), kInvalid);       // F = 0 / 0
  EXPECT_THAT(OneWayAnova({{1, 2}, {}}).status().message(), ::testing::HasSubstr("group 1"));
}

}  // namespace
}  // namespace dcs::report
