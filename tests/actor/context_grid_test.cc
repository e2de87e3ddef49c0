// Copyright 2026 The DCS Authors.
//
// Grids of contexts (actor/context_grid.h): how `--grid` is spelt and refused, the cells' order,
// and a policy's returns over a grid: the same whatever the number of threads, each cell the
// returns the evaluation protocol gives for that context and index.

#include "actor/context_grid.h"

#include <cmath>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::actor {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

absl::StatusOr<GridAxis> Parse(const char* text) {
  return ParseGridAxis(env::CartPole::Features(), text);
}

TEST(ContextGridTest, AnAxisIsFeatureLowHighCount) {
  absl::StatusOr<GridAxis> axis = Parse("length=0.1:2:20");
  ASSERT_TRUE(axis.ok()) << axis.status();
  EXPECT_EQ(axis->name, "length");
  EXPECT_EQ(axis->feature, *env::CartPole::Features().IndexOf("length"));
  EXPECT_EQ(axis->count, 20);
  EXPECT_DOUBLE_EQ(axis->value(0), 0.1);
  EXPECT_DOUBLE_EQ(axis->value(19), 2.0);
  EXPECT_DOUBLE_EQ(axis->value(1) - axis->value(0), 0.1);
  absl::StatusOr<GridAxis> single = Parse("gravity=9.8:9.8:1");
  ASSERT_TRUE(single.ok()) << single.status();
  EXPECT_DOUBLE_EQ(single->value(0), 9.8);
}

TEST(ContextGridTest, AMalformedAxisIsRefusedNamingItsText) {
  for (const char* text : {"length", "length=1:2", "length=a:2:3", "length=1:2:0",
                           "length=2:1:3", "length=1:2:1"}) {
    absl::StatusOr<GridAxis> axis = Parse(text);
    EXPECT_EQ(axis.status().code(), absl::StatusCode::kInvalidArgument) << text;
    EXPECT_THAT(axis.status().message(), HasSubstr(text));
  }
}

// The messages `dcs train` gives for a context (env::ContextSpace).
TEST(ContextGridTest, AnUnknownFeatureOrAValueOutOfRangeGetsTrainsMessage) {
  const env::ContextSpace& space = env::CartPole::Features();
  EXPECT_EQ(Parse("lenght=0.1:2:3").status(), space.IndexOf("lenght").status());
  const int length = *space.IndexOf("length");
  EXPECT_EQ(Parse("length=-1:2:3").status(), space.Validate(length, -1));
  EXPECT_FALSE(Parse("length=0.1:1e9:3").ok());
}

TEST(ContextGridTest, TheFirstAxisVariesFastest) {
  const std::vector<GridAxis> axes = {*Parse("length=0.5:1.5:3"), *Parse("gravity=5:10:2")};
  EXPECT_EQ(CellCount(axes), 6u);
  EXPECT_THAT(CellValues(axes, 0), ElementsAre(0.5, 5));
  EXPECT_THAT(CellValues(axes, 1), ElementsAre(1.0, 5));
  EXPECT_THAT(CellValues(axes, 3), ElementsAre(0.5, 10));
  EXPECT_THAT(CellValues(axes, 5), ElementsAre(1.5, 10));
}

// A small tanh policy of CartPole's 4 inputs and 2 actions, with random weights.
PolicyWeights SmallPolicy() {
  Random random(3);
  PolicyWeights weights{.num_actions = 2};
  int inputs = 4;
  for (int outputs : {16, 2}) {
    DenseLayer layer{.inputs = inputs,
                     .outputs = outputs,
                     .activation = outputs == 2 ? Activation::kNone : Activation::kTanh};
    for (int i = 0; i < inputs * outputs; ++i) {
      layer.weight.push_back(static_cast<float>(random.Normal(0, 1)));
    }
    layer.bias.assign(outputs, 0.0f);
    weights.layers.push_back(std::move(layer));
    inputs = outputs;
  }
  return weights;
}

TEST(ContextGridTest, ReturnsAreTheProtocolsWhateverTheThreads) {
  const std::vector<GridAxis> axes = {*Parse("length=0.2:1.4:4"), *Parse("gravity=5:15:3")};
  const PolicyWeights weights = SmallPolicy();
  const env::DynamicContextOptions base;
  absl::StatusOr<std::vector<ContextResult>> one =
      EvaluateGrid<env::CartPole>(weights, base, axes, 5, 11, 1);
  absl::StatusOr<std::vector<ContextResult>> three =
      EvaluateGrid<env::CartPole>(weights, base, axes, 5, 11, 3);
  ASSERT_TRUE(one.ok()) << one.status();
  ASSERT_TRUE(three.ok()) << three.status();
  ASSERT_EQ(one->size(), 12u);
  bool returns_differ = false;
  for (size_t c = 0; c < one->size(); ++c) {
    EXPECT_EQ((*one)[c].returns, (*three)[c].returns) << "cell " << c;
    returns_differ |= (*one)[c].mean != (*one)[0].mean;
    // Cell c as the protocol evaluates context index c, with the cell's context.
    env::DynamicContextOptions cell_base{.context = env::CartPole::Features().Defaults()};
    cell_base.context[axes[1].feature] = CellValues(axes, c)[1];
    PolicyNetwork policy = *PolicyNetwork::Create(weights);
    absl::StatusOr<ContextResult> expected = EvaluateContext<env::CartPole>(
        policy, cell_base, axes[0].feature, {.value = CellValues(axes, c)[0]}, c, 5, 11);
    ASSERT_TRUE(expected.ok()) << expected.status();
    EXPECT_EQ((*one)[c].returns, expected->returns) << "cell " << c;
    double mean = 0;
    for (double r : expected->returns) mean += r / 5;
    EXPECT_NEAR((*one)[c].mean, mean, 1e-9);
  }
  EXPECT_TRUE(returns_differ) << "every cell scored the same: the contexts had no effect";
}

TEST(ContextGridTest, AnInvalidCellIsRefusedBeforeAnyEpisode) {
  GridAxis length = *Parse("length=0.5:1:2");
  length.high = -1;  // as no parse would give: the cell's context is refused when evaluated
  absl::StatusOr<std::vector<ContextResult>> results =
      EvaluateGrid<env::CartPole>(SmallPolicy(), {}, {length}, 2, 0, 2);
  EXPECT_EQ(results.status().code(), absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::actor
