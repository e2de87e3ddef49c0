// Copyright 2026 The DCS Authors.
#include "run/schedule_yaml.h"

#include <string>
#include <variant>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::run {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::SizeIs;

std::string ErrorOf(const std::string& text) {
  absl::StatusOr<std::vector<env::ScheduleConfig>> configs =
      ParseScheduleConfigsYaml(text, "s.yaml");
  if (configs.ok()) return "OK";
  EXPECT_EQ(configs.status().code(), absl::StatusCode::kInvalidArgument);
  return std::string(configs.status().message());
}

TEST(ScheduleYamlTest, ReadsNumbersWordsListsAndParts) {
  absl::StatusOr<std::vector<env::ScheduleConfig>> configs = ParseScheduleConfigsYaml(R"(
- family: sudden_jump
  step_size_frac_range: [0.1, 0.2]
  direction: positive
  interval_range: [10, 20]
- family: sequential
  parts:
    - {family: sinusoidal, amplitude_frac: 0.5, period: 40}
    - {family: constant}
)",
                                                                                      "s.yaml");
  ASSERT_TRUE(configs.ok()) << configs.status();
  ASSERT_THAT(*configs, SizeIs(2));
  const env::ScheduleConfig& jump = (*configs)[0];
  EXPECT_EQ(jump.family, "sudden_jump");
  EXPECT_THAT(std::get<std::vector<double>>(jump.params.at("step_size_frac_range")),
              ElementsAre(0.1, 0.2));
  EXPECT_EQ(std::get<std::string>(jump.params.at("direction")), "positive");
  const env::ScheduleConfig& sequential = (*configs)[1];
  ASSERT_THAT(sequential.parts, SizeIs(2));
  EXPECT_EQ(std::get<double>(sequential.parts[0].params.at("period")), 40);
  EXPECT_EQ(sequential.parts[1].family, "constant");
}

TEST(ScheduleYamlTest, NumbersFollowTheStrictRule) {
  // strtod used to take these as numbers.
  EXPECT_THAT(ErrorOf("{family: sinusoidal, period: nan}"),
              AllOf(HasSubstr("s.yaml: period: line 1"), HasSubstr("must be a finite number")));
  EXPECT_THAT(ErrorOf("{family: sinusoidal, period: inf}"), HasSubstr("finite"));
  EXPECT_THAT(ErrorOf("{family: sudden_jump, interval_range: [10, nan]}"),
              AllOf(HasSubstr("interval_range[1]"), HasSubstr("finite")));
  // A quoted number is a word, which the family's reader refuses where it wants a number.
  absl::StatusOr<std::vector<env::ScheduleConfig>> quoted =
      ParseScheduleConfigsYaml("{family: sinusoidal, period: '125'}", "s.yaml");
  ASSERT_TRUE(quoted.ok()) << quoted.status();
  EXPECT_EQ(std::get<std::string>((*quoted)[0].params.at("period")), "125");
  EXPECT_FALSE(env::ParseScheduleSpec((*quoted)[0], 0.35, 0.75, 1).ok());
}

TEST(ScheduleYamlTest, MalformedSchedulesNameThePathAndLine) {
  EXPECT_THAT(ErrorOf("{period: 3}"), HasSubstr("needs a 'family'"));
  EXPECT_THAT(ErrorOf("family: sinusoidal\nperiod: 3\nperiod: 4\n"),
              HasSubstr("period: line 3: key 'period' given twice"));
  EXPECT_THAT(ErrorOf("family: sinusoidal\nperiod: {a: 1}\n"),
              HasSubstr("period: line 2: must be a number, a word or a list of numbers"));
  EXPECT_THAT(ErrorOf("- {family: constant}\n- {family: sequential, parts: 3}\n"),
              HasSubstr("[1].parts: line 2: must be a list of schedules"));
  EXPECT_THAT(ErrorOf("family: [a]\n"), HasSubstr("family: line 1: must be a name"));
  EXPECT_THAT(ErrorOf("[1, 2"), HasSubstr("s.yaml: line "));
}

TEST(ScheduleYamlTest, ScheduleSpecErrorsLandOnTheParameter) {
  YamlReader reader("run.yaml");
  absl::StatusOr<YAML::Node> root = reader.Load(R"(schedule:
  family: sequential
  parts:
    - {family: sinusoidal, period: 40}
    - family: cosine_annealing
      T_0: 0
)");
  ASSERT_TRUE(root.ok());
  absl::StatusOr<env::ScheduleConfig> config =
      ReadScheduleConfig(reader, (*root)["schedule"], "schedule");
  ASSERT_TRUE(config.ok()) << config.status();
  absl::StatusOr<env::ScheduleSpec> spec = env::ParseScheduleSpec(*config, 0.35, 0.75, 1);
  ASSERT_FALSE(spec.ok());
  EXPECT_THAT(ScheduleError(reader.errors(), "schedule", spec.status()).message(),
              AllOf(HasSubstr("run.yaml: schedule.parts[1].T_0: line 6: "),
                    HasSubstr("schedule 'cosine_annealing': T_0 ")));

  config->parts[1].family = "wobble";
  spec = env::ParseScheduleSpec(*config, 0.35, 0.75, 1);
  EXPECT_THAT(ScheduleError(reader.errors(), "schedule", spec.status()).message(),
              AllOf(HasSubstr("schedule.parts[1]: line 5: "), HasSubstr("'wobble'")));
}

}  // namespace
}  // namespace dcs::run
