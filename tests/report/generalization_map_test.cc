// Copyright 2026 The DCS Authors.
//
// Generalisation maps (report/generalization_map.h): one feature gives lines with bands and
// the training range marked; two give a heatmap panel per policy on one colour scale, with the
// training contexts drawn; malformed maps are refused. (Rendered by gnuplot and looked at in
// Chromium in tests/integration/eval_cli_test.cc.)

#include "report/generalization_map.h"

#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::SizeIs;

MapPolicy Policy(const std::string& label, size_t cells, double scale) {
  MapPolicy policy{.label = label};
  for (size_t c = 0; c < cells; ++c) {
    policy.means.push_back(scale * static_cast<double>(c));
    policy.stds.push_back(1);
  }
  return policy;
}

GeneralizationMap TwoFeatures() {
  GeneralizationMap map{.name = "generalization",
                        .title = "cartpole",
                        .axes = {{.feature = "length", .values = {0.5, 1.0, 1.5}},
                                 {.feature = "gravity", .values = {5, 10}}}};
  for (const double scale : {1.0, 2.0}) {
    MapPolicy policy = Policy(scale == 1 ? "static" : "sinusoidal", 6, scale);
    policy.training = {{.low = 0.35, .high = 0.75, .pool = {0.35, 0.55, 0.75}},
                       {.low = 9.8, .high = 9.8}};
    if (scale == 2) policy.training[1] = {.low = 5, .high = 10};  // trained on both
    map.policies.push_back(std::move(policy));
  }
  return map;
}

TEST(GeneralizationMapTest, TwoFeaturesGiveAHeatmapPerPolicyOnOneScale) {
  absl::StatusOr<GnuplotFigure> figure = GeneralizationMapFigure(TwoFeatures());
  ASSERT_TRUE(figure.ok()) << figure.status();
  ASSERT_THAT(figure->data, SizeIs(1));
  const std::vector<std::string> rows = absl::StrSplit(figure->data[0].csv, '\n',
                                                       absl::SkipEmpty());
  EXPECT_THAT(rows, SizeIs(1 + 2 * 6));
  EXPECT_EQ(rows[0], "panel,x,y,mean,std");
  EXPECT_EQ(rows[2], "0,1,5,1,1");  // the first feature varies fastest
  EXPECT_EQ(rows[12], "1,1.5,10,10,1");
  // One colour scale over both policies' means, and each panel its own rows.
  EXPECT_THAT(figure->script, HasSubstr("set cbrange [0:10]"));
  EXPECT_THAT(figure->script, HasSubstr("every ::0::5 "));
  EXPECT_THAT(figure->script, HasSubstr("every ::6::11 "));
  // Where each trained: its range at gravity 9.8, and its pool's three contexts.
  EXPECT_THAT(figure->script, HasSubstr("set arrow from 0.35,9.8 to 0.75,9.8 nohead"));
  EXPECT_THAT(figure->script, HasSubstr("set object rectangle from 0.35,5 to 0.75,10"));
  EXPECT_THAT(figure->script, HasSubstr("x,y\n0.35,9.8\n0.55,9.8\n0.75,9.8\nEOD"));
}

TEST(GeneralizationMapTest, OneFeatureGivesLinesWithTheTrainingRangeMarked) {
  GeneralizationMap map{.name = "length", .axes = {{.feature = "length", .values = {0.5, 1.0}}}};
  MapPolicy policy = Policy("static", 2, 100);
  policy.training = {{.low = 0.35, .high = 0.75, .pool = {0.35, 0.75}}};
  map.policies.push_back(policy);
  absl::StatusOr<GnuplotFigure> figure = GeneralizationMapFigure(map);
  ASSERT_TRUE(figure.ok()) << figure.status();
  // The line with its band of one std, then the pool as points.
  EXPECT_THAT(figure->data[0].csv, HasSubstr("0,0,1,100,99,101,"));
  EXPECT_THAT(figure->data[0].csv, HasSubstr("0,1,0.35,-1,"));
  EXPECT_THAT(figure->script, HasSubstr("0.35"));
  EXPECT_THAT(figure->script, HasSubstr("0.75"));
}

// Policies trained on one pool (a sweep's conditions) share one legend entry for it; policies
// on different pools each show their own.
TEST(GeneralizationMapTest, OneFeatureDrawsAPoolOnceForPoliciesTrainedOnIt) {
  GeneralizationMap map{.name = "length", .axes = {{.feature = "length", .values = {0.5, 1.0}}}};
  for (const std::string label : {"static", "sinusoidal"}) {
    MapPolicy policy = Policy(label, 2, 100);
    policy.training = {{.low = 0.35, .high = 0.75, .pool = {0.35, 0.75}}};
    map.policies.push_back(policy);
  }
  absl::StatusOr<GnuplotFigure> shared = GeneralizationMapFigure(map);
  ASSERT_TRUE(shared.ok()) << shared.status();
  EXPECT_THAT(shared->script, HasSubstr("'training pool'"));
  EXPECT_THAT(shared->script, Not(HasSubstr("training pool (")));

  map.policies[1].training[0].pool = {0.35, 0.55, 0.75};
  absl::StatusOr<GnuplotFigure> apart = GeneralizationMapFigure(map);
  ASSERT_TRUE(apart.ok()) << apart.status();
  EXPECT_THAT(apart->script, HasSubstr("'training pool (static)'"));
  EXPECT_THAT(apart->script, HasSubstr("'training pool (sinusoidal)'"));
}

TEST(GeneralizationMapTest, AMalformedMapIsRefused) {
  GeneralizationMap no_axes = TwoFeatures();
  no_axes.axes.clear();
  GeneralizationMap three_axes = TwoFeatures();
  three_axes.axes.push_back(three_axes.axes[0]);
  GeneralizationMap short_means = TwoFeatures();
  short_means.policies[1].means.pop_back();
  GeneralizationMap nan_mean = TwoFeatures();
  nan_mean.policies[0].means[2] = std::nan("");
  GeneralizationMap no_span = TwoFeatures();
  no_span.policies[0].training.pop_back();
  for (const GeneralizationMap& map : {no_axes, three_axes, short_means, nan_mean, no_span}) {
    EXPECT_EQ(GeneralizationMapFigure(map).status().code(),
              absl::StatusCode::kInvalidArgument);
  }
}

}  // namespace
}  // namespace dcs::report
