// Copyright 2026 The DCS Authors.
#include "run/yaml_splice.h"

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::run {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::Optional;

std::vector<KeyPathStep> Steps(absl::string_view path) {
  std::optional<std::vector<KeyPathStep>> steps = ParseKeyPath(path);
  EXPECT_TRUE(steps.has_value()) << path;
  return steps.value_or(std::vector<KeyPathStep>());
}

TEST(YamlSpliceTest, KeyPathsAreNamesAndIndices) {
  EXPECT_THAT(Steps("stages[1].schedule.T_0"),
              ElementsAre(KeyPathStep{.key = "stages"}, KeyPathStep{.index = 1},
                          KeyPathStep{.key = "schedule"}, KeyPathStep{.key = "T_0"}));
  EXPECT_THAT(Steps("a[0][12]"), ElementsAre(KeyPathStep{.key = "a"}, KeyPathStep{.index = 0},
                                             KeyPathStep{.index = 12}));
  EXPECT_THAT(Steps("initial_state-lower"),
              ElementsAre(KeyPathStep{.key = "initial_state-lower"}));
  for (const char* bad : {"", ".a", "a.", "a..b", "a[", "a[x]", "a[]", "a[1", "a b", "[0]",
                          "a.[0]", "a[-1]"}) {
    EXPECT_EQ(ParseKeyPath(bad), std::nullopt) << bad;
  }
  EXPECT_EQ(KeyPathText(Steps("stages[1].schedule.T_0")), "stages[1].schedule.T_0");
}

TEST(YamlSpliceTest, PathsOverlapWhenOneLeadsIntoTheOther) {
  EXPECT_TRUE(KeyPathsOverlap(Steps("schedule"), Steps("schedule.period")));
  EXPECT_TRUE(KeyPathsOverlap(Steps("stages[1].steps"), Steps("stages[1]")));
  EXPECT_TRUE(KeyPathsOverlap(Steps("pool.size"), Steps("pool.size")));
  EXPECT_FALSE(KeyPathsOverlap(Steps("schedule.period"), Steps("schedule.periodic")));
  EXPECT_FALSE(KeyPathsOverlap(Steps("stages[0].steps"), Steps("stages[1].steps")));
  EXPECT_FALSE(KeyPathsOverlap(Steps("ppo.gamma"), Steps("ppo.gae_lambda")));
}

TEST(YamlSpliceTest, PlacingCopiesThePathAndLeavesTheDocumentAlone) {
  const YAML::Node document = YAML::Load(R"(a: 1
stages:
  - {steps: 10, schedule: {family: constant}}
  - {steps: 20, schedule: {family: sinusoidal, period: 5}}
values: [7, 8]
)");
  const std::string before = YamlText(document);
  YamlArena arena(document);
  std::vector<std::string> created;
  const absl::StatusOr<YAML::Node> placed = WithValueAt(
      arena, document, Steps("stages[1].schedule.period"), document["values"][1], &created);
  ASSERT_TRUE(placed.ok()) << placed.status();
  EXPECT_THAT(created, IsEmpty());
  EXPECT_EQ(YamlText(*placed), R"(a: 1
stages:
  - {steps: 10, schedule: {family: constant}}
  - {steps: 20, schedule: {family: sinusoidal, period: 8}}
values: [7, 8]
)");
  EXPECT_EQ(YamlText(document), before);
  // The value keeps its line (5), and so does what was not copied.
  EXPECT_EQ((*placed)["stages"][1]["schedule"]["period"].Mark().line, 4);
  EXPECT_EQ((*placed)["stages"][0]["steps"].Mark().line, 2);

  // Mappings the path lacks are created, and said to be.
  const absl::StatusOr<YAML::Node> deeper =
      WithValueAt(arena, document, Steps("ppo.policy.layers"), document["values"], &created);
  ASSERT_TRUE(deeper.ok()) << deeper.status();
  EXPECT_THAT(created, ElementsAre("ppo.policy", "ppo"));
  EXPECT_EQ((*deeper)["ppo"]["policy"]["layers"][0].as<int>(), 7);
  EXPECT_FALSE(document["ppo"]);
}

TEST(YamlSpliceTest, PlacingSaysWhichStepCannotBeTaken) {
  const YAML::Node document = YAML::Load("a: 1\nlist: [1, 2]\n");
  YamlArena arena(document);
  const YAML::Node value = YAML::Load("3");
  auto error = [&](absl::string_view path) {
    absl::StatusOr<YAML::Node> placed = WithValueAt(arena, document, Steps(path), value);
    return placed.ok() ? std::string("OK") : std::string(placed.status().message());
  };
  EXPECT_EQ(error("a.b"), "a is a single value, not a mapping with 'b'");
  EXPECT_EQ(error("list.b"), "list is a list, not a mapping with 'b'");
  EXPECT_EQ(error("list[2]"), "list has 2 items, so no item 2");
  EXPECT_EQ(error("a[0]"), "there is no list a to take item 0 of");
  EXPECT_EQ(error("missing[0]"), "there is no list missing to take item 0 of");
  EXPECT_EQ(error("list[1]"), "OK");
}

TEST(YamlSpliceTest, MergedMappingsTakeTheOverridesKeys) {
  const YAML::Node base = YAML::Load("{a: 1, b: 2, c: 3}");
  const YAML::Node over = YAML::Load("{b: 20, d: 40}");
  YamlArena arena(base);
  const YAML::Node merged = MergedMapping(arena, base, over);
  EXPECT_EQ(YamlText(merged), "a: 1\nc: 3\nb: 20\nd: 40\n");
  EXPECT_THAT(FindKey(merged, "b"), Optional(testing::Property(&YAML::Node::Scalar, "20")));
  EXPECT_EQ(FindKey(merged, "e"), std::nullopt);
  EXPECT_EQ(FindKey(YAML::Load("[1]"), "a"), std::nullopt);
}

TEST(YamlSpliceTest, TextKeepsWhatTheReaderTellsApart) {
  const YAML::Node document =
      YAML::Load("a: \"125\"\nb: 3.0e-4\nc: {x: [1, 2]}\nd: null\ne: !!float 2\nf: 'yes'\n");
  EXPECT_EQ(YamlText(document),
            "a: \"125\"\nb: 3.0e-4\nc: {x: [1, 2]}\nd: ~\ne: 2\nf: \"yes\"\n");
  EXPECT_EQ(FlowText(document["c"]), "{x: [1, 2]}");
  EXPECT_EQ(FlowText(document["a"]), "125");
  EXPECT_EQ(FlowText(document["d"]), "null");
}

}  // namespace
}  // namespace dcs::run
