// Copyright 2026 The DCS Authors.
//
// Context features and their normalisation (docs/reference.md, "Observation modes and
// normalisation", env/context_feature.h).

#include "env/context_feature.h"

#include <cmath>
#include <limits>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

ContextFeature Feature(double lower, double upper, double norm_lower, double norm_upper) {
  return {.name = "f",
          .lower = lower,
          .upper = upper,
          .normalization_lower = norm_lower,
          .normalization_upper = norm_upper};
}

ContextSpace TwoFeatures() {
  return ContextSpace({{.name = "length", .default_value = 0.5, .lower = 0.05, .upper = 5.0,
                        .normalization_lower = 0.05, .normalization_upper = 2.0},
                       {.name = "com_x", .default_value = 0.0,
                        .lower = -std::numeric_limits<double>::infinity(),
                        .upper = std::numeric_limits<double>::infinity(),
                        .normalization_lower = -2.0, .normalization_upper = 2.0}});
}

TEST(ContextNormalizeTest, MapsTheSensorBoundsToMinusOnePlusOne) {
  // The paper's CartPole length bounds (0.05, 2.0): mid 1.025, half 0.975.
  const ContextFeature length = Feature(0.05, 5.0, 0.05, 2.0);
  EXPECT_FLOAT_EQ(NormalizeContext(length, 0.05), -1.0f);
  EXPECT_FLOAT_EQ(NormalizeContext(length, 2.0), 1.0f);
  EXPECT_FLOAT_EQ(NormalizeContext(length, 1.025), 0.0f);
  EXPECT_FLOAT_EQ(NormalizeContext(length, 0.55), static_cast<float>((0.55 - 1.025) / 0.975));
  EXPECT_NEAR(NormalizeContext(length, 0.55), -0.48718, 1e-5);
  // Beyond the sensor bounds the value is not squashed, only clipped at +-5.
  EXPECT_FLOAT_EQ(NormalizeContext(length, 3.0), static_cast<float>((3.0 - 1.025) / 0.975));
  // Walker / CarRacing COM bounds (-2, 2).
  const ContextFeature com = Feature(-10, 10, -2.0, 2.0);
  EXPECT_FLOAT_EQ(NormalizeContext(com, -0.6), -0.3f);
  EXPECT_FLOAT_EQ(NormalizeContext(com, 1.7), 0.85f);
}

TEST(ContextNormalizeTest, ClipsAtFive) {
  const ContextFeature com = Feature(-100, 100, -2.0, 2.0);
  EXPECT_FLOAT_EQ(NormalizeContext(com, 10.0), 5.0f);   // exactly at the clip
  EXPECT_FLOAT_EQ(NormalizeContext(com, 9.9), 4.95f);   // just inside
  EXPECT_EQ(NormalizeContext(com, 11.0), 5.0f);
  EXPECT_EQ(NormalizeContext(com, -50.0), -5.0f);
  EXPECT_EQ(NormalizeContext(com, std::numeric_limits<double>::infinity()), 5.0f);
  // Degenerate sensor bounds: half is floored at 1e-8, so any offset clips.
  const ContextFeature flat = Feature(0, 1, 0.5, 0.5);
  EXPECT_EQ(NormalizeContext(flat, 0.5), 0.0f);
  EXPECT_EQ(NormalizeContext(flat, 0.50001), 5.0f);
  EXPECT_EQ(NormalizeContext(flat, 0.49999), -5.0f);
}

TEST(ContextSpaceTest, IndexOfAndUnknownNames) {
  const ContextSpace space = TwoFeatures();
  EXPECT_EQ(space.size(), 2);
  absl::StatusOr<int> index = space.IndexOf("com_x");
  ASSERT_TRUE(index.ok());
  EXPECT_EQ(*index, 1);
  EXPECT_EQ(*space.IndexOf("length"), 0);
  EXPECT_EQ(space.feature(1).name, "com_x");
  const absl::Status unknown = space.IndexOf("lenght").status();
  EXPECT_EQ(unknown.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(unknown.message(), HasSubstr("lenght"));
  EXPECT_THAT(unknown.message(), HasSubstr("length, com_x"));
}

TEST(ContextSpaceTest, ValidateBoundsAndNaN) {
  const ContextSpace space = TwoFeatures();
  EXPECT_TRUE(space.Validate(0, 0.05).ok());  // bounds inclusive
  EXPECT_TRUE(space.Validate(0, 5.0).ok());
  EXPECT_TRUE(space.Validate(0, 2.5).ok());   // beyond the sensor bounds, within physical ones
  const absl::Status low = space.Validate(0, 0.04);
  EXPECT_EQ(low.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(low.message(), HasSubstr("length"));
  EXPECT_THAT(low.message(), HasSubstr("[0.05, 5]"));
  EXPECT_FALSE(space.Validate(0, 5.01).ok());
  EXPECT_FALSE(space.Validate(0, std::numeric_limits<double>::quiet_NaN()).ok());
  // Infinite bounds still refuse non-finite values.
  EXPECT_TRUE(space.Validate(1, -1e300).ok());
  EXPECT_FALSE(space.Validate(1, std::numeric_limits<double>::infinity()).ok());
  EXPECT_FALSE(space.Validate(1, std::numeric_limits<double>::quiet_NaN()).ok());
  EXPECT_THAT(space.Defaults(), ElementsAre(0.5, 0.0));
}

TEST(ContextSpaceTest, CartPoleFeatures) {
  const ContextSpace& space = CartPole::Features();
  EXPECT_EQ(space.size(), CartPole::kNumFeatures);
  EXPECT_EQ(*space.IndexOf("length"), CartPole::kLength);
  EXPECT_EQ(*space.IndexOf("gravity"), CartPole::kGravity);
  const ContextFeature& length = space.feature(CartPole::kLength);
  EXPECT_EQ(length.normalization_lower, 0.05);  // the paper's sensor bounds
  EXPECT_EQ(length.normalization_upper, 2.0);
  EXPECT_EQ(length.default_value, 0.5);
  EXPECT_THAT(space.IndexOf("pole_length").status().message(), HasSubstr("masspole"));
  // Every default is valid and every feature's sensor bounds are finite and ordered.
  const std::vector<double> defaults = space.Defaults();
  for (int i = 0; i < space.size(); ++i) {
    EXPECT_TRUE(space.Validate(i, defaults[i]).ok()) << i;
    EXPECT_TRUE(std::isfinite(space.feature(i).normalization_lower)) << i;
    EXPECT_LT(space.feature(i).normalization_lower, space.feature(i).normalization_upper) << i;
  }
}

}  // namespace
}  // namespace dcs::env
