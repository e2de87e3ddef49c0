// Copyright 2026 The DCS Authors.
#include "run/search_space_yaml.h"

#include <string>
#include <variant>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/search_space.h"
#include "tests/run/source_files.h"

namespace dcs::run {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr absl::string_view kStages = R"(
parameters:
  - {name: x, type: float, low: -5, high: 10}
  - {name: lr, type: float, low: 1e-5, high: 1e-2, log: true}
  - {name: frac, type: float, low: 0, high: 1, step: 0.25}
  - {name: layers, type: int, low: 1, high: 9, step: 2}
  - {name: mode, type: categorical, choices: [constant, sinusoidal, cosine]}
  - {name: period, type: int, low: 10, high: 500, log: true, when: {mode: sinusoidal}}
  - {name: radius, type: float, low: 0, high: 1, when: {mode: [sinusoidal, cosine]}}
)";

TEST(SearchSpaceYamlTest, ReadsEveryKindOfParameterInOrder) {
  const absl::StatusOr<SearchSpace> space = ParseSearchSpaceYaml(kStages, "space.yaml");
  ASSERT_TRUE(space.ok()) << space.status();
  ASSERT_EQ(space->parameters.size(), 7u);
  const auto& lr = std::get<FloatDistribution>(space->parameters[1].distribution);
  EXPECT_EQ(lr.low, 1e-5);
  EXPECT_TRUE(lr.log);
  EXPECT_EQ(std::get<FloatDistribution>(space->parameters[2].distribution).step, 0.25);
  EXPECT_EQ(std::get<IntDistribution>(space->parameters[3].distribution).step, 2);
  EXPECT_THAT(std::get<CategoricalDistribution>(space->parameters[4].distribution).choices,
              ElementsAre("constant", "sinusoidal", "cosine"));
  EXPECT_EQ(space->parameters[5].condition->parent, "mode");
  EXPECT_THAT(space->parameters[6].condition->choices, ElementsAre("sinusoidal", "cosine"));
}

TEST(SearchSpaceYamlTest, TheHeadersExampleParses) {
  const std::string example = HeaderExample("run/search_space_yaml.h");
  ASSERT_THAT(example, HasSubstr("parameters:"));
  const absl::StatusOr<SearchSpace> space = ParseSearchSpaceYaml(example, "example");
  ASSERT_TRUE(space.ok()) << space.status();
  EXPECT_EQ(space->parameters.size(), 6u);
}

TEST(SearchSpaceYamlTest, ConditionsFollowTheParentsChoice) {
  const SearchSpace space = *ParseSearchSpaceYaml(kStages, "space.yaml");
  const SearchParameter& period = space.parameters[5];
  const SearchParameter& radius = space.parameters[6];
  EXPECT_FALSE(IsActive(period, space, {}));
  EXPECT_FALSE(IsActive(period, space, {{"mode", 0}}));
  EXPECT_TRUE(IsActive(period, space, {{"mode", 1}}));
  EXPECT_FALSE(IsActive(period, space, {{"mode", 2}}));
  EXPECT_TRUE(IsActive(radius, space, {{"mode", 2}}));
  EXPECT_TRUE(IsActive(space.parameters[0], space, {}));
}

TEST(SearchSpaceTest, ContainsChecksRangeGridAndIntegrality) {
  EXPECT_TRUE(Contains(FloatDistribution{.low = 0, .high = 1, .step = 0.25}, 0.75));
  EXPECT_FALSE(Contains(FloatDistribution{.low = 0, .high = 1, .step = 0.25}, 0.7));
  EXPECT_FALSE(Contains(FloatDistribution{.low = 0, .high = 1}, 1.5));
  EXPECT_FALSE(Contains(FloatDistribution{.low = 0, .high = 1}, std::nan("")));
  EXPECT_TRUE(Contains(IntDistribution{.low = 1, .high = 9, .step = 2}, 5));
  EXPECT_FALSE(Contains(IntDistribution{.low = 1, .high = 9, .step = 2}, 4));
  EXPECT_FALSE(Contains(IntDistribution{.low = 1, .high = 9}, 2.5));
  EXPECT_TRUE(Contains(CategoricalDistribution{{"a", "b"}}, 1));
  EXPECT_FALSE(Contains(CategoricalDistribution{{"a", "b"}}, 2));
}

// Each bad space is refused with the file, and the parameter or the line, and the problem.
TEST(SearchSpaceYamlTest, BadSpacesAreRefusedNamingTheProblem) {
  const std::pair<const char*, const char*> cases[] = {
      {"parameters: []", "no parameters"},
      {"parameters: [{name: x, type: float, low: 1}]", "needs 'low' and 'high'"},
      {"parameters: [{name: x, type: real, low: 0, high: 1}]", "unknown type 'real'"},
      {"parameters: [{name: x, type: float, low: 2, high: 1}]", "parameter 'x': low 2 is above"},
      {"parameters: [{name: x, type: float, low: 0, high: 1, log: true}]", "needs low > 0"},
      {"parameters: [{name: x, type: float, low: 0, high: 1, step: 0.3}]", "does not divide"},
      {"parameters: [{name: x, type: int, low: 0.5, high: 3}]", "are integers"},
      {"parameters: [{name: x, type: int, low: 1, high: 9, log: true, step: 2}]", "step 1"},
      {"parameters: [{name: m, type: categorical, choices: [a, a]}]", "'a' is given twice"},
      {"parameters: [{name: x, type: float, low: 0, high: nan}]", "line 1"},
      {"parameters: [{name: x, type: float, low: 0, high: 1, color: red}]", "color"},
      {"parameters: [{name: x, type: float, low: 0, high: 1}, {name: x, type: int, low: 0, "
       "high: 1}]",
       "'x': the name is given twice"},
      {"parameters: [{name: x, type: float, low: 0, high: 1, when: {m: a}}]",
       "parent 'm' is not a categorical parameter before it"},
      {"parameters: [{name: m, type: categorical, choices: [a]}, {name: x, type: float, low: 0, "
       "high: 1, when: {m: b}}]",
       "choice 'b' is not one of 'm' (a)"},
  };
  for (const auto& [text, problem] : cases) {
    const absl::StatusOr<SearchSpace> space = ParseSearchSpaceYaml(text, "space.yaml");
    ASSERT_FALSE(space.ok()) << text;
    EXPECT_EQ(space.status().code(), absl::StatusCode::kInvalidArgument) << text;
    EXPECT_THAT(space.status().message(), HasSubstr("space.yaml")) << text;
    EXPECT_THAT(space.status().message(), HasSubstr(problem)) << text;
  }
}

// Issue 14 (found by tests/fuzz/sweep_spec_fuzzer): an int parameter's bound beyond int64_t was
// cast to it to see whether it is whole, which is undefined (UBSan: outside the range of
// representable values; the sanitizer job runs this test). It is refused as any fraction is.
TEST(SearchSpaceYamlTest, AnIntBoundBeyondSixtyFourBitsIsRefused) {
  for (const char* text : {"parameters: [{name: x, type: int, low: 0, high: 5.0e+53}]",
                           "parameters: [{name: x, type: int, low: -1.0e+19, high: 3}]",
                           "parameters: [{name: x, type: int, low: 0, high: 9, step: 1.0e+30}]"}) {
    const absl::StatusOr<SearchSpace> space = ParseSearchSpaceYaml(text, "space.yaml");
    EXPECT_EQ(space.status().code(), absl::StatusCode::kInvalidArgument) << text;
    EXPECT_THAT(space.status().message(), HasSubstr("integers that fit in 64 bits")) << text;
  }
}

}  // namespace
}  // namespace dcs::run
