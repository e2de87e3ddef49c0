// Copyright 2026 The DCS Authors.
#include "services/log.h"

#include <map>
#include <string>
#include <vector>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <grpc/support/log.h>

#include "absl/status/status.h"
#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::ContainsRegex;
using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::MatchesRegex;
using ::testing::Not;
using ::testing::StartsWith;

// The lines written to stderr by `log`, without their newlines; expects each to end in one.
template <typename F>
std::vector<std::string> CaptureLines(F log) {
  ::testing::internal::CaptureStderr();
  log();
  const std::string out = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(out.empty() || out.back() == '\n') << out;
  std::vector<std::string> lines = absl::StrSplit(out, '\n');
  lines.pop_back();  // after the last newline
  return lines;
}

// Parses one JSON object with protobuf's JSON parser; its fields, all strings here.
std::map<std::string, std::string> ParseJsonObject(const std::string& line) {
  google::protobuf::Struct object;
  const auto status = google::protobuf::util::JsonStringToMessage(line, &object);
  EXPECT_TRUE(status.ok()) << status.ToString() << " in: " << line;
  std::map<std::string, std::string> fields;
  for (const auto& [key, value] : object.fields()) {
    EXPECT_EQ(value.kind_case(), google::protobuf::Value::kStringValue) << key;
    fields[key] = value.string_value();
  }
  return fields;
}

TEST(LogTest, JsonIsOneObjectPerLineWithAllFields) {
  ConfigureLogging(
      {.component = "coordinator", .min_level = LogLevel::kInfo, .format = LogFormat::kJson});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kInfo, "worker registered", {{"worker_id", "actor-2"}, {"pid", 4242}});
    Log(LogLevel::kError, "second");
  });
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0], StartsWith("{\"time\":"));
  std::map<std::string, std::string> fields = ParseJsonObject(lines[0]);
  EXPECT_THAT(fields["time"],
              MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}\\.[0-9]{3}Z"));
  EXPECT_EQ(fields["level"], "info");
  EXPECT_EQ(fields["component"], "coordinator");
  EXPECT_EQ(fields["msg"], "worker registered");
  EXPECT_EQ(fields["worker_id"], "actor-2");
  EXPECT_EQ(fields["pid"], "4242");
  EXPECT_EQ(fields.size(), 6u);

  fields = ParseJsonObject(lines[1]);
  EXPECT_EQ(fields["level"], "error");
  EXPECT_EQ(fields["msg"], "second");
  EXPECT_EQ(fields.size(), 4u);
}

TEST(LogTest, JsonEscapesQuotesNewlinesAndControlCharacters) {
  ConfigureLogging({.component = "dcs", .min_level = LogLevel::kDebug, .format = LogFormat::kJson});
  const std::string message = "say \"hi\"\nnext line";
  const std::string control(
      "a\tb\x01"
      "c\r",
      6);
  const std::vector<std::string> lines = CaptureLines([&] {
    Log(LogLevel::kWarning, message, {{"path", "C:\\dir"}, {"control", control}});
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr(R"("msg":"say \"hi\"\nnext line")"));
  EXPECT_THAT(lines[0], HasSubstr(R"("control":"a\tb\u0001c\r")"));
  // And a JSON parser reads back exactly what was logged.
  std::map<std::string, std::string> fields = ParseJsonObject(lines[0]);
  EXPECT_EQ(fields["level"], "warning");
  EXPECT_EQ(fields["msg"], message);
  EXPECT_EQ(fields["path"], "C:\\dir");
  EXPECT_EQ(fields["control"], control);
}

TEST(LogTest, JsonEscapesKeysAndComponent) {
  ConfigureLogging(
      {.component = "co\"mp", .min_level = LogLevel::kInfo, .format = LogFormat::kJson});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kInfo, "m", {{"k\"ey", "v"}});
  });
  ASSERT_EQ(lines.size(), 1u);
  std::map<std::string, std::string> fields = ParseJsonObject(lines[0]);
  EXPECT_EQ(fields["component"], "co\"mp");
  EXPECT_EQ(fields["k\"ey"], "v");
}

TEST(LogTest, TextFormatHasTimeLevelComponentAndFields) {
  ConfigureLogging(
      {.component = "coordinator", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kInfo, "worker registered", {{"worker_id", "actor-2"}});
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], MatchesRegex("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}\\."
                                     "[0-9]{3}Z INFO coordinator: worker registered "
                                     "worker_id=actor-2"));
}

TEST(LogTest, TextFormatQuotesValuesThatAreNotOneToken) {
  ConfigureLogging(
      {.component = "actor", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kWarning, "retrying",
        {{"error", "UNAVAILABLE: connection refused"},
         {"empty", ""},
         {"eq", "a=b"},
         {"quote", "say \"x\""},
         {"plain", "127.0.0.1:5"}});
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr(" WARNING actor: retrying "));
  EXPECT_THAT(lines[0], HasSubstr(R"( error="UNAVAILABLE: connection refused")"));
  EXPECT_THAT(lines[0], HasSubstr(R"( empty="")"));
  EXPECT_THAT(lines[0], HasSubstr(R"( eq="a=b")"));
  EXPECT_THAT(lines[0], HasSubstr(R"( quote="say \"x\"")"));
  EXPECT_THAT(lines[0], EndsWith(" plain=127.0.0.1:5"));
}

TEST(LogTest, TextValueWithNewlineStaysOnOneLine) {
  ConfigureLogging(
      {.component = "actor", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kInfo, "m", {{"error", "first\nsecond"}});
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], EndsWith(R"(error="first\nsecond")"));
}

// log.h promises one line per event, so the text format escapes a newline in the message.
TEST(LogTest, TextMessageWithNewlineStaysOnOneLine) {
  ConfigureLogging(
      {.component = "actor", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kInfo, "first\nsecond", {{"k", "v"}});
  });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr("first"));
  EXPECT_THAT(lines[0], HasSubstr("second"));
}

TEST(LogTest, MinLevelFiltersLowerLevels) {
  ConfigureLogging(
      {.component = "learner", .min_level = LogLevel::kWarning, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kDebug, "debug message");
    Log(LogLevel::kInfo, "info message");
    Log(LogLevel::kWarning, "warning message");
    Log(LogLevel::kError, "error message");
  });
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0], HasSubstr("WARNING learner: warning message"));
  EXPECT_THAT(lines[1], HasSubstr("ERROR learner: error message"));
}

TEST(LogTest, DebugLevelShowsEverything) {
  ConfigureLogging(
      {.component = "learner", .min_level = LogLevel::kDebug, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] {
    Log(LogLevel::kDebug, "d");
    Log(LogLevel::kInfo, "i");
  });
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0], ContainsRegex(" DEBUG learner: d$"));
  EXPECT_THAT(lines[1], ContainsRegex(" INFO learner: i$"));
}

TEST(LogTest, ReconfiguringChangesFormat) {
  ConfigureLogging({.component = "a", .min_level = LogLevel::kInfo, .format = LogFormat::kJson});
  ConfigureLogging({.component = "b", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] { Log(LogLevel::kInfo, "m"); });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], Not(StartsWith("{")));
  EXPECT_THAT(lines[0], HasSubstr(" INFO b: m"));
}

// The names the --log-level flag accepts are the ones JSON lines carry.
TEST(LogTest, JsonLevelIsTheFlagName) {
  const std::vector<std::pair<std::string, LogLevel>> names = LogLevelNames();
  ASSERT_EQ(names.size(), 4u);
  for (const auto& [name, level] : names) {
    ConfigureLogging({.component = "c", .min_level = LogLevel::kDebug, .format = LogFormat::kJson});
    ::testing::internal::CaptureStderr();
    Log(level, "m");
    EXPECT_THAT(::testing::internal::GetCapturedStderr(),
                HasSubstr("\"level\":\"" + name + "\""));
  }
}

TEST(GrpcLogCaptureTest, HoldsGrpcErrorsInsteadOfLogging) {
  ConfigureLogging({.component = "t", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  std::string errors;
  const std::vector<std::string> lines = CaptureLines([&] {
    GrpcLogCapture capture;
    gpr_log(GPR_ERROR, "first %s", "problem");
    gpr_log(GPR_ERROR, "second problem");
    errors = capture.errors();
  });
  EXPECT_EQ(errors, "first problem; second problem");
  EXPECT_TRUE(lines.empty()) << lines[0];
}

TEST(GrpcLogCaptureTest, GrpcErrorsAreLoggedAsWarningsOtherwise) {
  ConfigureLogging({.component = "t", .min_level = LogLevel::kInfo, .format = LogFormat::kText});
  const std::vector<std::string> lines = CaptureLines([] { gpr_log(GPR_ERROR, "grpc says no"); });
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0], HasSubstr(" WARNING t: grpc says no source=grpc file="));
}

}  // namespace
}  // namespace dcs::services
