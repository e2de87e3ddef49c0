// Copyright 2026 The DCS Authors.
#include "services/command_line.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/time/time.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/exit_codes.h"
#include "tests/testing/temp_dir.h"

namespace dcs::services {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;

int CountLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

enum class Shape { kRound, kSquare };

// The flags of a small program, parsed by ParseCommandLine.
struct Flags {
  std::string config;
  std::string name = "default-name";
  int worker_count = 1;
  std::vector<std::string> tags;
  bool verbose = false;
  absl::Duration timeout = absl::Seconds(5);
  Shape shape = Shape::kSquare;
};

class CommandLineTest : public dcs::testing::TempDirTest {
 protected:
  // Writes a config file and returns its path.
  std::string WriteConfig(const std::string& contents, const std::string& name = "config.yaml") {
    return WritePlain(name, contents);
  }

  void AddFlags(CLI::App& app, bool with_config = true) {
    if (with_config) app.add_option("--config", flags_.config, "YAML file of flag values");
    app.add_option("--name", flags_.name, "a string");
    app.add_option("--worker-count", flags_.worker_count, "an int");
    app.add_option("--tag", flags_.tags, "a list");
    app.add_flag("--verbose", flags_.verbose, "a flag");
    AddDurationOption(app, "--timeout", &flags_.timeout, "a duration");
    AddChoiceOption(app, "-s,--shape", &flags_.shape,
                    {{"round", Shape::kRound}, {"square", Shape::kSquare}}, "a choice");
  }

  // Parses `args` (without the program name) into flags_, capturing stderr into stderr_.
  std::optional<int> Parse(const std::vector<std::string>& args, bool with_config = true) {
    CLI::App app("a test program", "dcs-test");
    AddFlags(app, with_config);
    std::vector<const char*> argv = {"dcs-test"};
    for (const std::string& arg : args) argv.push_back(arg.c_str());
    ::testing::internal::CaptureStderr();
    const std::optional<int> result =
        ParseCommandLine(app, static_cast<int>(argv.size()), argv.data());
    stderr_ = ::testing::internal::GetCapturedStderr();
    return result;
  }

  Flags flags_;
  std::string stderr_;
};

TEST_F(CommandLineTest, CommandLineAloneSetsFlags) {
  EXPECT_EQ(Parse({"--name", "alpha", "--worker-count=7", "--tag", "a", "--tag", "b", "--verbose",
                   "--timeout", "1500ms"}),
            std::nullopt)
      << stderr_;
  EXPECT_EQ(flags_.name, "alpha");
  EXPECT_EQ(flags_.worker_count, 7);
  EXPECT_THAT(flags_.tags, ElementsAre("a", "b"));
  EXPECT_TRUE(flags_.verbose);
  EXPECT_EQ(flags_.timeout, absl::Milliseconds(1500));
  EXPECT_EQ(stderr_, "");
}

TEST_F(CommandLineTest, NoArgumentsKeepsDefaults) {
  EXPECT_EQ(Parse({}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.name, "default-name");
  EXPECT_EQ(flags_.worker_count, 1);
  EXPECT_THAT(flags_.tags, IsEmpty());
  EXPECT_FALSE(flags_.verbose);
  EXPECT_EQ(flags_.timeout, absl::Seconds(5));
}

TEST_F(CommandLineTest, ConfigValuesAreApplied) {
  const std::string path = WriteConfig(
      "name: from-file\n"
      "worker-count: 3\n"
      "tag: [x, y, z]\n"
      "verbose: true\n"
      "timeout: 250ms\n");
  EXPECT_EQ(Parse({"--config", path}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.config, path);
  EXPECT_EQ(flags_.name, "from-file");
  EXPECT_EQ(flags_.worker_count, 3);
  EXPECT_THAT(flags_.tags, ElementsAre("x", "y", "z"));
  EXPECT_TRUE(flags_.verbose);
  EXPECT_EQ(flags_.timeout, absl::Milliseconds(250));
}

TEST_F(CommandLineTest, ConfigPathWithEqualsSign) {
  const std::string path = WriteConfig("name: from-file\n");
  EXPECT_EQ(Parse({"--config=" + path}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.name, "from-file");
}

TEST_F(CommandLineTest, BlockListValues) {
  const std::string path = WriteConfig("tag:\n  - first\n  - second\n");
  EXPECT_EQ(Parse({"--config", path}), std::nullopt) << stderr_;
  EXPECT_THAT(flags_.tags, ElementsAre("first", "second"));
}

TEST_F(CommandLineTest, UnderscoresAndDashesInKeysAreAlike) {
  EXPECT_EQ(Parse({"--config", WriteConfig("worker_count: 4\n", "underscore.yaml")}), std::nullopt)
      << stderr_;
  EXPECT_EQ(flags_.worker_count, 4);
  EXPECT_EQ(Parse({"--config", WriteConfig("worker-count: 5\n", "dash.yaml")}), std::nullopt)
      << stderr_;
  EXPECT_EQ(flags_.worker_count, 5);
}

TEST_F(CommandLineTest, ValuesNotOnTheCommandLineComeFromConfig) {
  const std::string path = WriteConfig("name: from-file\nworker_count: 3\n");
  EXPECT_EQ(Parse({"--config", path, "--verbose"}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.name, "from-file");
  EXPECT_EQ(flags_.worker_count, 3);
  EXPECT_TRUE(flags_.verbose);
}

// The command line wins over the config file (command_line.h).
TEST_F(CommandLineTest, CommandLineWinsOverConfig) {
  const std::string path = WriteConfig("name: from-file\nworker_count: 3\ntimeout: 1s\n");
  EXPECT_EQ(Parse({"--name", "from-command-line", "--config", path, "--timeout=2s"}), std::nullopt)
      << stderr_;
  EXPECT_EQ(flags_.name, "from-command-line");
  EXPECT_EQ(flags_.timeout, absl::Seconds(2));
  EXPECT_EQ(flags_.worker_count, 3);
}

TEST_F(CommandLineTest, EmptyConfigFileChangesNothing) {
  EXPECT_EQ(Parse({"--config", WriteConfig("")}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.name, "default-name");
  EXPECT_EQ(flags_.worker_count, 1);
}

TEST_F(CommandLineTest, UnknownConfigKeyIsOneLineNamingTheKey) {
  const std::string path = WriteConfig("name: ok\nlissten: 0.0.0.0:1\n");
  EXPECT_EQ(Parse({"--config", path}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, StartsWith("dcs-test: error: "));
  EXPECT_THAT(stderr_, HasSubstr("'lissten'"));
  EXPECT_THAT(stderr_, HasSubstr(path));
}

TEST_F(CommandLineTest, ConfigKeyNamedConfigIsRejected) {
  const std::string path = WriteConfig("config: other.yaml\n");
  EXPECT_EQ(Parse({"--config", path}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr("'config'"));
}

TEST_F(CommandLineTest, MalformedYamlNamesTheLine) {
  const std::string path = WriteConfig("name: alpha\nworker_count: 3\nkey: value: other\n");
  EXPECT_EQ(Parse({"--config", path}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr("line 3"));
  EXPECT_THAT(stderr_, HasSubstr(path));
}

TEST_F(CommandLineTest, ConfigThatIsNotAMappingIsRejected) {
  EXPECT_EQ(Parse({"--config", WriteConfig("- name\n- alpha\n")}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
}

TEST_F(CommandLineTest, NestedConfigValueIsRejected) {
  EXPECT_EQ(Parse({"--config", WriteConfig("name:\n  first: a\n")}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr("name"));
}

TEST_F(CommandLineTest, MissingConfigFileIsConfigError) {
  const std::string path = Path("absent.yaml");
  EXPECT_EQ(Parse({"--config", path}), kExitConfig);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr(path));
}

TEST_F(CommandLineTest, UnknownFlagIsUsageErrorOnOneLine) {
  EXPECT_EQ(Parse({"--bogus-flag=1"}), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, StartsWith("dcs-test: error: "));
  EXPECT_THAT(stderr_, HasSubstr("--bogus-flag"));
}

TEST_F(CommandLineTest, BadIntegerIsUsageError) {
  EXPECT_EQ(Parse({"--worker-count", "many"}), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
}

TEST_F(CommandLineTest, HelpExitsOkAndPrintsFlagsOnStdout) {
  ::testing::internal::CaptureStdout();
  const std::optional<int> result = Parse({"--help"});
  const std::string out = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(result, kExitOk);
  EXPECT_THAT(out, HasSubstr("--worker-count"));
  EXPECT_THAT(out, HasSubstr("--timeout"));
  EXPECT_EQ(stderr_, "");
}

TEST_F(CommandLineTest, BadDurationIsUsageError) {
  EXPECT_EQ(Parse({"--timeout", "soon"}), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr("soon"));
  EXPECT_EQ(flags_.timeout, absl::Seconds(5));
}

TEST_F(CommandLineTest, NegativeDurationIsUsageError) {
  EXPECT_EQ(Parse({"--timeout=-1s"}), kExitUsage);
  EXPECT_EQ(flags_.timeout, absl::Seconds(5));
}

TEST_F(CommandLineTest, BadDurationInConfigIsUsageError) {
  EXPECT_EQ(Parse({"--config", WriteConfig("timeout: 5 parsecs\n")}), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
}

TEST_F(CommandLineTest, DurationUnits) {
  for (const auto& [text, expected] :
       std::vector<std::pair<std::string, absl::Duration>>{{"500ms", absl::Milliseconds(500)},
                                                           {"5s", absl::Seconds(5)},
                                                           {"2m", absl::Minutes(2)},
                                                           {"1h30m", absl::Minutes(90)},
                                                           {"0", absl::ZeroDuration()}}) {
    EXPECT_EQ(Parse({"--timeout", text}), std::nullopt) << text << ": " << stderr_;
    EXPECT_EQ(flags_.timeout, expected) << text;
  }
}

TEST_F(CommandLineTest, ProgramWithoutConfigOptionParsesNormally) {
  EXPECT_EQ(Parse({"--name", "plain", "--worker-count", "2"}, /*with_config=*/false), std::nullopt)
      << stderr_;
  EXPECT_EQ(flags_.name, "plain");
  EXPECT_EQ(flags_.worker_count, 2);
}

TEST_F(CommandLineTest, ProgramWithoutConfigOptionDoesNotReadConfigFiles) {
  const std::string path = WriteConfig("name: from-file\n");
  EXPECT_EQ(Parse({"--config", path}, /*with_config=*/false), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_EQ(flags_.name, "default-name");
}

TEST_F(CommandLineTest, ChoiceSetsItsValueByLongOrShortName) {
  EXPECT_EQ(Parse({"--shape", "round"}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.shape, Shape::kRound);
  EXPECT_EQ(Parse({"-s", "square"}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.shape, Shape::kSquare);
}

TEST_F(CommandLineTest, ChoiceFromConfigAndCommandLineWins) {
  const std::string path = WriteConfig("shape: round\n");
  EXPECT_EQ(Parse({"--config", path}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.shape, Shape::kRound);
  EXPECT_EQ(Parse({"-s", "square", "--config", path}), std::nullopt) << stderr_;
  EXPECT_EQ(flags_.shape, Shape::kSquare);
}

TEST_F(CommandLineTest, UnknownChoiceIsUsageErrorListingTheAllowedWords) {
  EXPECT_EQ(Parse({"--shape", "oval"}), kExitUsage);
  EXPECT_EQ(CountLines(stderr_), 1) << stderr_;
  EXPECT_THAT(stderr_, HasSubstr("--shape: 'oval' is not one of round, square"));
  EXPECT_EQ(flags_.shape, Shape::kSquare);
}

TEST_F(CommandLineTest, HelpShowsTheChoicesAndTheDefault) {
  ::testing::internal::CaptureStdout();
  EXPECT_EQ(Parse({"--help"}), kExitOk);
  const std::string help = ::testing::internal::GetCapturedStdout();
  EXPECT_THAT(help, HasSubstr("{round,square}"));
  EXPECT_THAT(help, HasSubstr("=square"));
}

TEST(PrintErrorTest, PrintsOneLineWithProgramName) {
  ::testing::internal::CaptureStderr();
  PrintError("dcs-coordinator", "config file c.yaml: unknown key 'lissten'");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "dcs-coordinator: error: config file c.yaml: unknown key 'lissten'\n");
}

}  // namespace
}  // namespace dcs::services
