// Copyright 2026 The DCS Authors.
//
// The enumerations a run config names, against their one tables (common/enum_names.h): each
// value has one name, names are distinct, and the names a run config accepts are the table's.
// (Schedule families: tests/env/schedule_config_test.cc and the static_assert beside their
// table; splits against the proto: tests/run/evaluation_log_test.cc.)

#include <set>
#include <string>

#include "absl/strings/str_format.h"
#include "actor/split.h"
#include "common/enum_names.h"
#include "env/observe_mode.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_spec_yaml.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

template <typename E, size_t N>
void ExpectOneNameEach(const EnumName<E> (&table)[N]) {
  std::set<std::string> names;
  for (const auto& [value, name] : table) {
    EXPECT_TRUE(names.insert(std::string(name)).second) << name;
    EXPECT_EQ(NameOf(table, value), name);
    EXPECT_EQ(FindByName(table, name), value);
  }
  EXPECT_EQ(FindByName(table, "no such name"), std::nullopt);
}

constexpr char kConfig[] = R"(env: cartpole
feature: length
observe: %s
evaluation: {contexts: {%s: [0.5]}}
)";

absl::StatusOr<RunSpec> Config(absl::string_view observe, absl::string_view split) {
  return ParseRunSpecYaml(absl::StrFormat(kConfig, observe, split), "run.yaml");
}

TEST(EnumNamesTest, ObserveModesAreTheConfigsWords) {
  ExpectOneNameEach(env::kObserveModeNames);
  EXPECT_EQ(ListNames(env::kObserveModeNames), "none, initial or live");
  for (const auto& [mode, name] : env::kObserveModeNames) {
    absl::StatusOr<RunSpec> spec = Config(name, "id");
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(spec->observe, mode);
  }
  EXPECT_THAT(Config("blind", "id").status().message(),
              HasSubstr("observe: line 3: must be none, initial or live, got 'blind'"));
}

TEST(EnumNamesTest, SplitsAreTheConfigsEvaluationKeys) {
  ExpectOneNameEach(actor::kSplitNames);
  for (const auto& [split, name] : actor::kSplitNames) {
    absl::StatusOr<RunSpec> spec = Config("none", name);
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_THAT(spec->eval_values(split), ::testing::ElementsAre(0.5)) << name;
  }
  EXPECT_THAT(Config("none", "ood").status().message(),
              HasSubstr("allowed: id, ood_low, ood_high"));
}

}  // namespace
}  // namespace dcs::run
