// Copyright 2026 The DCS Authors.
//
// `dcs study create/ask/tell/best` as a user outside DCS runs them: on a local --store file, and
// on a coordinator that is killed (SIGKILL) and restarted mid-study.

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include <filesystem>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/exit_codes.h"
#include "tests/integration/browser.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;

RunResult Dcs(const std::vector<std::string>& args) { return RunProgram(BinaryPath("dcs"), args); }

google::protobuf::Struct Json(const std::string& text) {
  google::protobuf::Struct json;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(text, &json).ok()) << text;
  return json;
}

class StudyCliTest : public dcs::testing::TempDirTest {};

TEST_F(StudyCliTest, AskTellAndBestThroughTheClient) {
  const std::string store = Path("studies.db");
  ASSERT_TRUE(WriteFileAtomically(Path("space.yaml"), R"(parameters:
  - {name: x, type: float, low: -2, high: 2}
  - {name: shape, type: categorical, choices: [bowl, ridge]}
)")
                  .ok());
  const RunResult create = Dcs({"study", "create", "--space", Path("space.yaml"), "--seed", "1",
                                "--sampler", "tpe", "--store", store});
  ASSERT_EQ(create.exit_code, services::kExitOk) << create.output;
  const std::string study(absl::StripAsciiWhitespace(create.output));
  EXPECT_EQ(study, "study-1");

  double best = 1e9;
  int best_trial = -1;
  for (int i = 0; i < 14; ++i) {
    const RunResult ask = Dcs({"study", "ask", study, "--store", store});
    ASSERT_EQ(ask.exit_code, services::kExitOk) << ask.output;
    const google::protobuf::Struct trial = Json(ask.output);
    const auto& params = trial.fields().at("params").struct_value().fields();
    const std::string shape = params.at("shape").string_value();
    ASSERT_TRUE(shape == "bowl" || shape == "ridge") << ask.output;
    const double x = params.at("x").number_value();
    const double value = shape == "bowl" ? x * x : 1 + x;
    const int number = static_cast<int>(trial.fields().at("trial").number_value());
    EXPECT_EQ(number, i);
    const RunResult tell = Dcs({"study", "tell", study, absl::StrCat(number),
                                absl::StrFormat("%.17g", value), "--store", store});
    ASSERT_EQ(tell.exit_code, services::kExitOk) << tell.output;
    if (value < best) {
      best = value;
      best_trial = number;
    }
  }
  const RunResult best_run = Dcs({"study", "best", study, "--store", store});
  ASSERT_EQ(best_run.exit_code, services::kExitOk) << best_run.output;
  const google::protobuf::Struct answer = Json(best_run.output);
  EXPECT_EQ(answer.fields().at("trial").number_value(), best_trial);
  EXPECT_NEAR(answer.fields().at("value").number_value(), best, 1e-12 * (1 + std::abs(best)));

  // Every trial, one JSON line each, complete.
  const RunResult trials = Dcs({"study", "trials", study, "--store", store, "-o", "json"});
  ASSERT_EQ(trials.exit_code, services::kExitOk) << trials.output;
  const std::vector<std::string> lines =
      absl::StrSplit(absl::StripTrailingAsciiWhitespace(trials.output), '\n');
  ASSERT_EQ(lines.size(), 14u) << trials.output;
  for (const std::string& line : lines) {
    EXPECT_EQ(Json(line).fields().at("state").string_value(), "complete") << line;
  }

  // The optimisation history, drawn by gnuplot and looked at in Chromium: the Okabe-Ito blue
  // dots (each value) and vermillion steps (the best so far) are on the page.
  const RunResult plot = Dcs({"study", "plot", study, "--out", Path("figures"), "--store", store});
  ASSERT_EQ(plot.exit_code, services::kExitOk) << plot.output;
  const std::string svg = Path("figures/study-1_history.svg");
  EXPECT_EQ(absl::StripAsciiWhitespace(plot.output), svg);
  EXPECT_THAT(ReadFile(svg).value_or(""), HasSubstr("<text>trial</text>"));
  const Screenshot image = TakeScreenshot(svg, Path("figures/shot.png"), 700, 450);
  int blue = 0;
  int vermillion = 0;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const int r = image.rgb[i], g = image.rgb[i + 1], b = image.rgb[i + 2];
    if (std::abs(r - 0) < 30 && std::abs(g - 114) < 30 && std::abs(b - 178) < 30) ++blue;
    if (std::abs(r - 213) < 30 && std::abs(g - 94) < 30 && std::abs(b - 0) < 30) ++vermillion;
  }
  EXPECT_GT(blue, 14 * 10) << "the dots";
  EXPECT_GT(vermillion, 300) << "the steps";

  // A finished trial is not told again; an unknown study is named.
  const RunResult again = Dcs({"study", "tell", study, "0", "1.0", "--store", store});
  EXPECT_EQ(again.exit_code, services::kExitFailure);
  EXPECT_THAT(again.output, HasSubstr("trial 0 of study-1 has finished"));
  const RunResult unknown = Dcs({"study", "ask", "study-9", "--store", store});
  EXPECT_THAT(unknown.output, HasSubstr("no study study-9"));
}

TEST_F(StudyCliTest, ABadSpaceIsRefusedNamingTheFileAndCreatesNothing) {
  ASSERT_TRUE(WriteFileAtomically(Path("space.yaml"),
                                  "parameters: [{name: x, type: float, low: 0, high: 1, "
                                  "log: true}]\n")
                  .ok());
  const RunResult create =
      Dcs({"study", "create", "--space", Path("space.yaml"), "--store", Path("s.db")});
  EXPECT_EQ(create.exit_code, services::kExitDataError) << create.output;
  EXPECT_THAT(create.output, HasSubstr(Path("space.yaml")));
  EXPECT_THAT(create.output, HasSubstr("a log range needs low > 0"));
  EXPECT_FALSE(std::filesystem::exists(Path("s.db"))) << "the refused study made its store";
  ASSERT_TRUE(WriteFileAtomically(Path("space.yaml"),
                                  "parameters: [{name: x, type: float, low: 0, high: 1}]\n")
                  .ok());
  ASSERT_EQ(
      Dcs({"study", "create", "--space", Path("space.yaml"), "--store", Path("s.db")}).exit_code,
      0);
  const RunResult value = Dcs({"study", "tell", "study-1", "0", "many", "--store", Path("s.db")});
  EXPECT_EQ(value.exit_code, services::kExitDataError);
  EXPECT_THAT(value.output, HasSubstr("VALUE must be a number"));
}

// Only `study create` makes a store: every other command refuses a path that holds none, and
// creates no file there.
TEST_F(StudyCliTest, ACommandOnAMissingStoreIsRefusedAndCreatesNothing) {
  const std::string typo = Path("typo.db");
  for (const std::vector<std::string>& command :
       std::vector<std::vector<std::string>>{{"ask", "study-1"},
                                             {"tell", "study-1", "0", "1"},
                                             {"report", "study-1", "0", "10", "1"},
                                             {"trials", "study-1"},
                                             {"best", "study-1"},
                                             {"plot", "study-1", "--out", Path("figures")}}) {
    std::vector<std::string> args = {"study"};
    args.insert(args.end(), command.begin(), command.end());
    args.insert(args.end(), {"--store", typo});
    const RunResult result = Dcs(args);
    EXPECT_EQ(result.exit_code, services::kExitNoInput) << command[0] << ": " << result.output;
    EXPECT_THAT(result.output, HasSubstr("no study store " + typo)) << command[0];
    EXPECT_FALSE(std::filesystem::exists(typo)) << command[0] << " created it";
  }
}

// Runs `trials` trials of the space.yaml study `study` (x², or 1 + x on the ridge) through
// `dcs study` with `where` (--store FILE or --addr ADDRESS); returns each trial's JSON.
std::vector<std::string> RunTrials(const std::string& study, int trials,
                                   const std::vector<std::string>& where) {
  std::vector<std::string> asked;
  for (int i = 0; i < trials; ++i) {
    std::vector<std::string> ask = {"study", "ask", study};
    ask.insert(ask.end(), where.begin(), where.end());
    const RunResult answer = Dcs(ask);
    EXPECT_EQ(answer.exit_code, services::kExitOk) << answer.output;
    asked.push_back(answer.output);
    const google::protobuf::Struct trial = Json(answer.output);
    const auto& params = trial.fields().at("params").struct_value().fields();
    const double x = params.at("x").number_value();
    const double value = params.at("shape").string_value() == "bowl" ? x * x : 1 + x;
    std::vector<std::string> tell = {"study", "tell", study,
                                     absl::StrCat(trial.fields().at("trial").number_value()),
                                     absl::StrFormat("%.17g", value)};
    tell.insert(tell.end(), where.begin(), where.end());
    const RunResult told = Dcs(tell);
    EXPECT_EQ(told.exit_code, services::kExitOk) << told.output;
  }
  return asked;
}

// A study on the coordinator survives the coordinator's death: restarted on its data directory,
// it goes on from the trials it acknowledged, and asks what an uninterrupted study asks (the
// same trials as a local store with the same seed: the sampler keeps no state between trials).
TEST_F(StudyCliTest, AStudyOnTheCoordinatorSurvivesItsDeath) {
  ASSERT_TRUE(WriteFileAtomically(Path("space.yaml"), R"(parameters:
  - {name: x, type: float, low: -2, high: 2}
  - {name: shape, type: categorical, choices: [bowl, ridge]}
)")
                  .ok());
  const std::vector<std::string> local = {"--store", Path("local.db")};
  const RunResult local_study = Dcs({"study", "create", "--space", Path("space.yaml"), "--seed",
                                     "7", "--store", Path("local.db")});
  ASSERT_EQ(local_study.exit_code, services::kExitOk) << local_study.output;
  const std::vector<std::string> uninterrupted = RunTrials("study-1", 16, local);

  ClusterProcesses cluster(absl::Seconds(5));
  cluster.StartCoordinator();
  const std::vector<std::string> remote = {"--addr", cluster.coordinator_address()};
  const RunResult create = Dcs({"study", "create", "--space", Path("space.yaml"), "--seed", "7",
                                "--addr", cluster.coordinator_address()});
  ASSERT_EQ(create.exit_code, services::kExitOk) << create.output;
  const std::string study(absl::StripAsciiWhitespace(create.output));
  std::vector<std::string> asked = RunTrials(study, 9, remote);
  cluster.Kill("coordinator");
  const RunResult down =
      Dcs({"study", "ask", study, "--addr", cluster.coordinator_address(), "--timeout", "1s"});
  EXPECT_EQ(down.exit_code, services::kExitUnavailable) << down.output;
  cluster.StartCoordinator();
  const std::vector<std::string> rest = RunTrials(study, 7, remote);
  asked.insert(asked.end(), rest.begin(), rest.end());
  EXPECT_EQ(asked, uninterrupted);
}

// Reports through the coordinator get its pruner's answer; a pruned trial is told so.
TEST_F(StudyCliTest, ReportsGetThePrunersAnswer) {
  ClusterProcesses cluster(absl::Seconds(5));
  cluster.StartCoordinator();
  const std::string addr = cluster.coordinator_address();
  const RunResult create =
      Dcs({"study", "create", "--space", DCS_SOURCE_DIR "/bench/study/branin.yaml", "--pruner",
           "median", "--pruner-startup-trials", "1", "--addr", addr});
  ASSERT_EQ(create.exit_code, services::kExitOk) << create.output;
  const std::string study(absl::StripAsciiWhitespace(create.output));
  ASSERT_EQ(Dcs({"study", "ask", study, "--addr", addr}).exit_code, services::kExitOk);
  EXPECT_EQ(Dcs({"study", "report", study, "0", "1", "3.0", "--addr", addr}).output, "continue\n");
  ASSERT_EQ(Dcs({"study", "tell", study, "0", "3.0", "--addr", addr}).exit_code, services::kExitOk);
  ASSERT_EQ(Dcs({"study", "ask", study, "--addr", addr}).exit_code, services::kExitOk);
  EXPECT_EQ(Dcs({"study", "report", study, "1", "1", "8.0", "--addr", addr}).output, "prune\n");
  ASSERT_EQ(Dcs({"study", "tell", study, "1", "--state", "pruned", "--addr", addr}).exit_code,
            services::kExitOk);
  const google::protobuf::Struct best = Json(Dcs({"study", "best", study, "--addr", addr}).output);
  EXPECT_EQ(best.fields().at("trial").number_value(), 0);
}

}  // namespace
}  // namespace dcs::integration
