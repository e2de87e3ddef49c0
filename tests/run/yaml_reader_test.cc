// Copyright 2026 The DCS Authors.
#include "run/yaml_reader.h"

#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::run {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// `text` as a document of `x.yaml`; its key `value`.
YAML::Node Value(YamlReader& reader, const std::string& text) {
  absl::StatusOr<YAML::Node> root = reader.Load(text);
  EXPECT_TRUE(root.ok()) << root.status();
  return root.ok() ? (*root)["value"] : YAML::Node();
}

// The message of reading `value: <scalar>` with `read`, or "OK".
template <typename Read>
std::string ErrorOf(const std::string& scalar, Read read) {
  YamlReader reader("x.yaml");
  const YAML::Node node = Value(reader, absl::StrCat("a: 1\nvalue: ", scalar, "\n"));
  const absl::Status status = read(reader, node).status();
  if (status.ok()) return "OK";
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  return std::string(status.message());
}

auto Number = [](YamlReader& r, const YAML::Node& n) { return r.Number(n, "value"); };
auto Int = [](YamlReader& r, const YAML::Node& n) { return r.Int(n, "value"); };
auto Uint64 = [](YamlReader& r, const YAML::Node& n) { return r.Uint64(n, "value"); };
auto NumberOrWord = [](YamlReader& r, const YAML::Node& n) { return r.NumberOrWord(n, "value"); };

TEST(YamlReaderTest, NumbersArePlainFiniteScalarsEverywhere) {
  YamlReader reader("x.yaml");
  EXPECT_EQ(*reader.Number(Value(reader, "value: 0.25"), "value"), 0.25);
  EXPECT_EQ(*reader.Number(Value(reader, "value: +3e-4"), "value"), 3e-4);
  EXPECT_EQ(*reader.Number(Value(reader, "value: !!float 2"), "value"), 2);
  for (const char* not_finite : {"nan", "inf", "-inf", "NaN", "infinity"}) {
    EXPECT_THAT(ErrorOf(not_finite, Number),
                AllOf(HasSubstr("x.yaml: value: line 2: "), HasSubstr("must be a finite number"),
                      HasSubstr(not_finite)));
  }
  EXPECT_THAT(ErrorOf(".inf", Number), HasSubstr("must be a number, got '.inf'"));
  EXPECT_THAT(ErrorOf("\"0.25\"", Number), HasSubstr("must be a number, got the string \"0.25\""));
  EXPECT_THAT(ErrorOf("'7'", Int), HasSubstr("got the string \"7\""));
  EXPECT_THAT(ErrorOf("0x10", Number), HasSubstr("must be a number, got '0x10'"));
  EXPECT_THAT(ErrorOf("~", Number), HasSubstr("must be a number, got null"));
  EXPECT_THAT(ErrorOf("[1, 2]", Number), HasSubstr("got a list"));
  EXPECT_THAT(ErrorOf("{a: 1}", Number), HasSubstr("got a mapping"));
}

TEST(YamlReaderTest, IntegersAreExactAndInRange) {
  YamlReader reader("x.yaml");
  EXPECT_EQ(*reader.Int64(Value(reader, "value: 3e6"), "value"), 3'000'000);
  EXPECT_EQ(*reader.Int(Value(reader, "value: +12"), "value"), 12);
  EXPECT_EQ(*reader.Uint64(Value(reader, "value: 18446744073709551615"), "value"),
            std::numeric_limits<uint64_t>::max());
  EXPECT_THAT(ErrorOf("2.5", Int), HasSubstr("must be an integer, got '2.5'"));
  EXPECT_THAT(ErrorOf("nan", Int), HasSubstr("must be an integer, got 'nan'"));
  EXPECT_THAT(ErrorOf("3000000000", Int), HasSubstr("[-2147483648, 2147483647]"));
  EXPECT_THAT(ErrorOf("1e300", Int), HasSubstr("[-2147483648, 2147483647]"));
  EXPECT_THAT(ErrorOf("-1", Uint64), HasSubstr("must be a non-negative integer"));
  // Above 2^53 a number written with an exponent no longer names one integer.
  EXPECT_THAT(ErrorOf("1e17", Uint64), HasSubstr("must be a non-negative integer in"));
}

TEST(YamlReaderTest, NumberOrWordFollowsTheNumberRule) {
  YamlReader reader("x.yaml");
  EXPECT_EQ(std::get<double>(*reader.NumberOrWord(Value(reader, "value: 125"), "value")), 125);
  EXPECT_EQ(std::get<std::string>(*reader.NumberOrWord(Value(reader, "value: up"), "value")),
            "up");
  // Quoted, a number is a word (the family's reader then says it must be a number).
  EXPECT_EQ(std::get<std::string>(*reader.NumberOrWord(Value(reader, "value: '125'"), "value")),
            "125");
  EXPECT_THAT(ErrorOf("nan", NumberOrWord), HasSubstr("must be a finite number, got 'nan'"));
  EXPECT_THAT(ErrorOf("inf", NumberOrWord), HasSubstr("must be a finite number"));
}

TEST(YamlReaderTest, KeysAreKnownNamesGivenOnce) {
  YamlReader reader("x.yaml");
  absl::StatusOr<YAML::Node> root = reader.Load("ppo:\n  gamma: 0.9\n  gama: 0.9\n");
  ASSERT_TRUE(root.ok());
  std::vector<std::string> read;
  const absl::Status unknown = reader.ForEachKey(
      (*root)["ppo"], "ppo", {"gamma", "gae_lambda"},
      [&](const std::string&, const YAML::Node&, const std::string& path) {
        read.push_back(path);
        return absl::OkStatus();
      });
  EXPECT_THAT(unknown.message(),
              AllOf(HasSubstr("x.yaml: ppo.gama: line 3: unknown key 'gama' in ppo"),
                    HasSubstr("(allowed: gamma, gae_lambda)")));
  EXPECT_THAT(read, ElementsAre("ppo.gamma"));

  root = reader.Load("a: 1\nb: 2\na: 3\n");
  ASSERT_TRUE(root.ok());
  const absl::Status twice = reader.ForEachEntry(
      *root, "", [](const std::string&, const YAML::Node&, const std::string&) {
        return absl::OkStatus();
      });
  EXPECT_THAT(twice.message(), HasSubstr("a: line 3: key 'a' given twice"));

  root = reader.Load("- 1\n- 2\n");
  ASSERT_TRUE(root.ok());
  EXPECT_THAT(reader.ForEachKey(*root, "", {"a"},
                                [](const std::string&, const YAML::Node&, const std::string&) {
                                  return absl::OkStatus();
                                })
                  .message(),
              HasSubstr("must be a mapping with keys a"));
}

TEST(YamlReaderTest, ListsNameTheirItems) {
  YamlReader reader("x.yaml");
  absl::StatusOr<YAML::Node> root = reader.Load("values:\n  - 1\n  - 2\n  - two\n");
  ASSERT_TRUE(root.ok());
  EXPECT_THAT(reader.Numbers((*root)["values"], "values").status().message(),
              HasSubstr("x.yaml: values[2]: line 4: must be a number, got 'two'"));
  root = reader.Load("values: 3\n");
  ASSERT_TRUE(root.ok());
  EXPECT_THAT(reader.Ints((*root)["values"], "values").status().message(),
              HasSubstr("values: line 1: must be a list of integers"));
}

TEST(YamlReaderTest, ErrorsFoundLaterCarryTheLinesOfTheFieldsRead) {
  YamlReader reader("run.yaml");
  absl::StatusOr<YAML::Node> root = reader.Load("a: 1\npool:\n  values: [0.4, 0.9]\n");
  ASSERT_TRUE(root.ok());
  ASSERT_TRUE(reader
                  .ForEachKey((*root)["pool"], "pool", {"values"},
                              [&](const std::string&, const YAML::Node& value,
                                  const std::string& path) {
                                return reader.Numbers(value, path).status();
                              })
                  .ok());
  const ConfigErrors errors = reader.errors();
  EXPECT_EQ(errors.At("pool.values[1]", "must be within [0.35, 0.75]").message(),
            "run.yaml: pool.values[1]: line 3: must be within [0.35, 0.75]");
  EXPECT_EQ(errors.At("seed", "unread").message(), "run.yaml: seed: unread");
  EXPECT_EQ(ConfigErrors().At("ppo.gamma", "must be in [0, 1]").message(),
            "ppo.gamma: must be in [0, 1]");
}

TEST(YamlReaderTest, ErrorsShowPathsThroughThePathMapWithTheLinesOfTheNodesRead) {
  // As a sweep spec shows a trial's `ppo` keys where its condition wrote them.
  YamlReader reader("sweep.yaml", [](absl::string_view path) {
    return absl::StartsWith(path, "ppo") ? absl::StrCat("conditions[2].", path)
                                         : std::string(path);
  });
  absl::StatusOr<YAML::Node> root = reader.Load("a: 1\nppo: {gama: 0.9, gamma: 2}\n");
  ASSERT_TRUE(root.ok());
  const absl::Status unknown = reader.ForEachKey(
      (*root)["ppo"], "ppo", {"gamma"},
      [](const std::string&, const YAML::Node&, const std::string&) { return absl::OkStatus(); });
  EXPECT_EQ(unknown.message(),
            "sweep.yaml: conditions[2].ppo.gama: line 2: unknown key 'gama' in "
            "conditions[2].ppo (allowed: gamma)");
  ASSERT_TRUE(reader
                  .ForEachEntry((*root)["ppo"], "ppo",
                                [](const std::string&, const YAML::Node&, const std::string&) {
                                  return absl::OkStatus();
                                })
                  .ok());
  EXPECT_EQ(reader.errors().At("ppo.gamma", "must be in [0, 1], got 2").message(),
            "sweep.yaml: conditions[2].ppo.gamma: line 2: must be in [0, 1], got 2");
  EXPECT_EQ(reader.Error("a", (*root)["a"], "bad").message(), "sweep.yaml: a: line 1: bad");
}

TEST(YamlReaderTest, MalformedYamlNamesLineAndColumn) {
  YamlReader reader("x.yaml");
  EXPECT_THAT(reader.Load("a: [1, 2\nb: 3\n").status().message(),
              AllOf(HasSubstr("x.yaml: line "), HasSubstr("column ")));
}

}  // namespace
}  // namespace dcs::run
