// Copyright 2026 The DCS Authors.
#include "run/config_keys.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/config_errors.h"
#include "run/yaml_reader.h"

namespace dcs::run {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

// A config with a field of each kind a table reads, and defaults that are not zero.
struct Settings {
  int count = 3;
  int64_t steps = 1000;
  uint64_t seed = 7;
  double rate = 0.25;
  bool on = true;
  std::optional<double> limit;
  std::string name = "x";
  std::vector<int> widths = {8, 8};
  std::vector<double> values;
  int unread = 0;
};

const KeyTable<Settings>& Keys() {
  static const KeyTable<Settings>* const keys = new KeyTable<Settings>({
      {.name = "count", .meaning = "m", .field = &Settings::count, .bound = AtLeast(1)},
      {.name = "steps", .meaning = "m", .field = &Settings::steps},
      {.name = "seed", .meaning = "m", .field = &Settings::seed},
      {.name = "rate", .meaning = "m", .field = &Settings::rate, .bound = Within(0, 1)},
      {.name = "on", .meaning = "m", .field = &Settings::on},
      {.name = "limit", .meaning = "m", .field = &Settings::limit, .bound = Positive()},
      {.name = "name", .meaning = "m", .field = &Settings::name, .type = "one of {x, y}"},
      {.name = "widths",
       .meaning = "m",
       .field = &Settings::widths,
       .bound = Positive(),
       .items = "widths"},
      {.name = "values", .meaning = "m", .field = &Settings::values},
      {.name = "extra", .meaning = "read by hand", .type = "mapping", .default_value = "none"},
  });
  return *keys;
}

// `text` read through the table into Settings{}; the first error's message, or "OK".
std::string Read(const std::string& text, Settings& settings) {
  YamlReader reader("s.yaml");
  absl::StatusOr<YAML::Node> root = reader.Load(text);
  EXPECT_TRUE(root.ok()) << root.status();
  const absl::Status status = reader.ForEachKey(
      *root, "", Keys().names(),
      [&](const std::string& key, const YAML::Node& value, const std::string& path) {
        return ReadField(reader, Keys()[key], value, path, settings);
      });
  return status.ok() ? "OK" : std::string(status.message());
}

TEST(ConfigKeysTest, BoundsStateTheirRuleAsErrorsDo) {
  EXPECT_EQ(AtLeast(1).Rule(), "at least 1");
  EXPECT_EQ(Positive().Rule(), "positive");
  EXPECT_EQ(Within(0, 1).Rule(), "in [0, 1]");
  EXPECT_EQ(Within(1, 10000).Rule(), "in [1, 10000]");
  EXPECT_FALSE(Bound().bounded());
  EXPECT_TRUE(Positive().bounded());

  EXPECT_TRUE(Positive().Contains(1e-9));
  EXPECT_FALSE(Positive().Contains(0));
  EXPECT_TRUE(AtLeast(0).Contains(0));
  EXPECT_TRUE(Within(0, 1).Contains(1));
  EXPECT_FALSE(Within(0, 1).Contains(1.5));
  // Only finite numbers are in a bound.
  EXPECT_FALSE(Positive().Contains(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(AtLeast(0).Contains(std::nan("")));
}

TEST(ConfigKeysTest, TheReaderAllowsTheTablesKeysInItsOrder) {
  EXPECT_THAT(Keys().names(), ElementsAre("count", "steps", "seed", "rate", "on", "limit", "name",
                                          "widths", "values", "extra"));
  Settings settings;
  EXPECT_EQ(Read("cont: 1\n", settings),
            "s.yaml: cont: line 1: unknown key 'cont' at the top level (allowed: count, steps, "
            "seed, rate, on, limit, name, widths, values, extra)");
}

TEST(ConfigKeysTest, EachFieldIsReadAsItsTypeIs) {
  Settings settings;
  ASSERT_EQ(Read("count: 5\nsteps: 3e6\nseed: 9\nrate: 0.5\non: false\nlimit: 2\nname: y\n"
                 "widths: [4]\nvalues: [0.1, 0.2]\n",
                 settings),
            "OK");
  EXPECT_EQ(settings.count, 5);
  EXPECT_EQ(settings.steps, 3'000'000);
  EXPECT_EQ(settings.seed, 9u);
  EXPECT_EQ(settings.rate, 0.5);
  EXPECT_FALSE(settings.on);
  EXPECT_EQ(settings.limit, 2.0);
  EXPECT_EQ(settings.name, "y");
  EXPECT_THAT(settings.widths, ElementsAre(4));
  EXPECT_THAT(settings.values, ElementsAre(0.1, 0.2));
  EXPECT_EQ(settings.unread, 0);

  // An optional number takes null for none.
  ASSERT_EQ(Read("limit: null\n", settings), "OK");
  EXPECT_FALSE(settings.limit.has_value());

  // The reader's errors, at the key's path.
  EXPECT_EQ(Read("count: 1.5\n", settings), "s.yaml: count: line 1: must be an integer, got '1.5'");
  EXPECT_EQ(Read("seed: x\n", settings),
            "s.yaml: seed: line 1: must be a non-negative integer, got 'x'");
  EXPECT_EQ(Read("widths: 4\n", settings), "s.yaml: widths: line 1: must be a list of integers");
}

TEST(ConfigKeysTest, CheckBoundsNamesEachFieldOutsideItsBoundInTheTablesOrder) {
  Settings settings{.count = 0, .rate = 2, .limit = -1, .widths = {8, 0, -1}};
  ConfigProblems problems;
  const std::set<absl::string_view> outside =
      CheckBounds(Keys(), settings, "s", ConfigErrors(), problems);
  EXPECT_THAT(outside, ElementsAre("count", "limit", "rate", "widths"));
  std::vector<std::string> messages;
  for (const absl::Status& problem : problems.problems()) {
    messages.emplace_back(problem.message());
  }
  EXPECT_THAT(messages, ElementsAre("s.count: must be at least 1, got 0",
                                    "s.rate: must be in [0, 1], got 2",
                                    "s.limit: must be positive, got -1",
                                    "s.widths: must be a list of positive widths, got 0"));

  ConfigProblems none;
  EXPECT_THAT(CheckBounds(Keys(), Settings(), "s", ConfigErrors(), none), IsEmpty());
  EXPECT_TRUE(none.empty());  // an unset optional is not checked
}

TEST(ConfigKeysTest, DescribeTakesTypesFromFieldsAndDefaultsFromTheDefaultInstance) {
  const std::vector<KeyDoc> docs = Describe(Keys());
  ASSERT_EQ(docs.size(), Keys().keys().size());
  std::vector<std::string> rows;
  for (const KeyDoc& doc : docs) {
    rows.push_back(absl::StrCat(doc.name, " | ", doc.type, " | ", doc.default_value, " | ",
                                doc.range, " | ", doc.meaning));
  }
  EXPECT_THAT(rows, ElementsAre("count | integer | 3 | at least 1 | m",
                                "steps | integer | 1000 |  | m",
                                "seed | non-negative integer | 7 |  | m",
                                "rate | number | 0.25 | in [0, 1] | m",
                                "on | bool | true |  | m",
                                "limit | number or null | null | positive | m",
                                "name | one of {x, y} | x |  | m",
                                "widths | list of integers | [8, 8] | each positive | m",
                                "values | list of numbers | [] |  | m",
                                "extra | mapping | none |  | read by hand"));
}

}  // namespace
}  // namespace dcs::run
