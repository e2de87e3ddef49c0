// Copyright 2026 The DCS Authors.
#include "run/study_config.h"

#include <string>
#include <variant>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_spec_yaml.h"
#include "run/search_space_yaml.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

// A CartPole run of two stages that give only their steps: the study fills their schedules.
constexpr char kBase[] = R"(env: cartpole
total_timesteps: 150000
feature: length
training_range: [0.35, 0.75]
pool: {size: 7}
observe: live
evaluation: {freq: 30000, episodes: 5, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0]}}
stages:
  - {steps: 60000}
  - {steps: 90000}
)";

constexpr char kStages[] = R"(parameters:
  - {name: "stages[0].schedule.family", type: categorical, choices: [constant, sinusoidal]}
  - {name: "stages[0].schedule.period", type: int, low: 25, high: 500, log: true,
     when: {"stages[0].schedule.family": sinusoidal}}
  - {name: "stages[0].schedule.amplitude_frac", type: float, low: 0.05, high: 1,
     when: {"stages[0].schedule.family": sinusoidal}}
  - {name: "stages[1].schedule.family", type: categorical, choices: [constant, cosine_annealing]}
  - {name: "stages[1].schedule.T_0", type: int, low: 25, high: 500, log: true,
     when: {"stages[1].schedule.family": cosine_annealing}}
  - {name: ppo.learning_rate, type: float, low: 1e-5, high: 1e-3, log: true}
)";

TEST(TrialRunConfigTest, WritesEachValueAtItsKeyPath) {
  const SearchSpace space = *ParseSearchSpaceYaml(kStages, "space.yaml");
  const absl::StatusOr<SeededRuns> config =
      TrialRunConfig(kBase, "study.yaml", space,
                     {{"stages[0].schedule.family", 1},
                      {"stages[0].schedule.period", 125},
                      {"stages[0].schedule.amplitude_frac", 0.4},
                      {"stages[1].schedule.family", 1},
                      {"stages[1].schedule.T_0", 250},
                      {"ppo.learning_rate", 2.5e-4}});
  ASSERT_TRUE(config.ok()) << config.status();
  // The text reads back to the spec the trial carries.
  const absl::StatusOr<RunSpec> run = ParseRunSpecYaml(config->config_text(), "trial");
  ASSERT_TRUE(run.ok()) << run.status() << "\n" << config->config_text();
  ASSERT_EQ(config->spec().stages.size(), 2u);
  EXPECT_EQ(config->spec().stages[1].schedule.params, run->stages[1].schedule.params);
  EXPECT_EQ(config->spec().ppo.learning_rate, 2.5e-4);
  ASSERT_EQ(run->stages.size(), 2u);
  EXPECT_EQ(run->stages[0].steps, 60000);
  // Numbers as numbers (a quoted one would be a word to the schedule), floats to the last bit.
  const auto& first = run->stages[0].schedule;
  EXPECT_EQ(first.family, "sinusoidal");
  EXPECT_EQ(std::get<double>(first.params.at("period")), 125);
  EXPECT_EQ(std::get<double>(first.params.at("amplitude_frac")), 0.4);
  EXPECT_EQ(run->stages[1].schedule.family, "cosine_annealing");
  EXPECT_EQ(std::get<double>(run->stages[1].schedule.params.at("T_0")), 250);
  EXPECT_EQ(run->ppo.learning_rate, 2.5e-4);
}

TEST(TrialRunConfigTest, AConstantStageGetsOnlyItsFamily) {
  const SearchSpace space = *ParseSearchSpaceYaml(kStages, "space.yaml");
  const absl::StatusOr<SeededRuns> config = TrialRunConfig(kBase, "study.yaml", space,
                                                           {{"stages[0].schedule.family", 0},
                                                            {"stages[1].schedule.family", 0},
                                                            {"ppo.learning_rate", 3e-4}});
  ASSERT_TRUE(config.ok()) << config.status();
  const RunSpec& run = config->spec();
  EXPECT_EQ(run.stages[0].schedule.family, "constant");
  EXPECT_TRUE(run.stages[0].schedule.params.empty());
}

TEST(TrialRunConfigTest, BadPathsAndValuesAreRefusedNamingTheParameter) {
  SearchSpace not_a_path = *ParseSearchSpaceYaml(
      "parameters: [{name: \"stages[0]..family\", type: float, low: 0, high: 1}]", "s");
  EXPECT_THAT(ValidateStudyKeyPaths(not_a_path).message(), HasSubstr("is not a run config's key"));
  const SearchSpace overlapping = *ParseSearchSpaceYaml(
      "parameters: [{name: ppo, type: float, low: 0, high: 1}, "
      "{name: ppo.gamma, type: float, low: 0, high: 1}]",
      "s");
  EXPECT_THAT(ValidateStudyKeyPaths(overlapping).message(), HasSubstr("overlapping"));
  // Past the end of the base's stages.
  const SearchSpace third_stage = *ParseSearchSpaceYaml(
      "parameters: [{name: \"stages[2].steps\", type: int, low: 1, high: 9}]", "s");
  EXPECT_THAT(
      TrialRunConfig(kBase, "study.yaml", third_stage, {{"stages[2].steps", 3}}).status().message(),
      HasSubstr("parameter 'stages[2].steps'"));
  // A value the run config refuses: the family's parameter is out of its range.
  const SearchSpace learning_rate = *ParseSearchSpaceYaml(
      "parameters: [{name: ppo.learning_rate, type: float, low: -1, high: 1}]", "s");
  EXPECT_EQ(TrialRunConfig(kBase, "study.yaml", learning_rate, {{"ppo.learning_rate", -0.5}})
                .status()
                .code(),
            absl::StatusCode::kInvalidArgument);
  // A choice that YAML would not read back as one plain scalar.
  const SearchSpace unplain = *ParseSearchSpaceYaml(
      "parameters: [{name: observe, type: categorical, choices: [\"[a\"]}]", "s");
  EXPECT_THAT(TrialRunConfig(kBase, "study.yaml", unplain, {{"observe", 0}}).status().message(),
              HasSubstr("'[a' is not a plain YAML scalar"));
  // A value of no parameter.
  EXPECT_THAT(
      TrialRunConfig(kBase, "study.yaml", learning_rate, {{"ppo.gamma", 0.9}}).status().message(),
      HasSubstr("the space lacks"));
}

}  // namespace
}  // namespace dcs::run
