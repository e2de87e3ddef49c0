// Copyright 2026 The DCS Authors.
#include "run/appended_evaluation_log.h"

#include <filesystem>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "tests/testing/temp_dir.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

// A run's log as of its `count`th evaluation: 100 steps apart, with returns from `seed`, the
// last at a stage boundary so that best-anytime is chosen among them.
v1::EvaluationLog LogOf(int count, double seed = 0) {
  std::vector<actor::EvaluationResult> evaluations;
  for (int i = 0; i < count; ++i) {
    actor::EvaluationResult evaluation{
        .step = 100 * (i + 1),
        .updates = i + 1,
        .contexts = {{.context = {.split = actor::Split::kId, .value = 0.5},
                      .returns = {seed + i, seed + 2 * i},
                      .seconds = 0.25},
                     {.context = {.split = actor::Split::kOodHigh, .value = 1.0},
                      .returns = {seed - i}}}};
    actor::Summarize(evaluation);  // ood_low has no context: its summary is NaN
    evaluations.push_back(std::move(evaluation));
  }
  RunSpec spec;
  spec.env = "cartpole";
  spec.seed = 4;
  return MakeEvaluationLog(spec, evaluations, {200}, count == 4);
}

// Bit for bit, NaNs included (MessageDifferencer would call NaN unequal to itself).
void ExpectSameLog(const absl::StatusOr<v1::EvaluationLog>& read, const v1::EvaluationLog& log) {
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->evaluations_size(), log.evaluations_size());
  EXPECT_EQ(read->SerializeAsString(), log.SerializeAsString())
      << read->DebugString() << "\nwanted\n" << log.DebugString();
}

class AppendedEvaluationLogTest : public testing::TempDirTest {
 protected:
  std::string Dir() const { return dir().string(); }
  std::string Lines() const { return ReadFile(Path("evaluations.jsonl")).value_or(""); }

  // Appends evaluations [first, count) of LogOf(count).
  void AppendUpTo(int first, int count) {
    ASSERT_TRUE(AppendEvaluationLog(Dir(), first, EvaluationLogSince(LogOf(count), first)).ok());
  }
};

TEST_F(AppendedEvaluationLogTest, CheckpointsAppendOnlyTheirNewEvaluations) {
  EXPECT_FALSE(HasAppendedEvaluationLog(Dir()));
  AppendUpTo(0, 1);
  AppendUpTo(1, 3);
  EXPECT_TRUE(HasAppendedEvaluationLog(Dir()));
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(3));
  AppendUpTo(3, 4);
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(4));
  // One line per evaluation, each an Evaluation in JSON.
  const std::vector<std::string> lines = absl::StrSplit(Lines(), '\n');
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[4], "");
  EXPECT_THAT(lines[1], HasSubstr("\"step\":\"200\""));
  // The summary counts them.
  const std::string json = ReadFile(Path("evaluations.summary.json")).value_or("");
  EXPECT_THAT(json, HasSubstr("\"evaluations\": \"4\""));
}

TEST_F(AppendedEvaluationLogTest, ACrashsUnfinishedAppendIsNeitherReadNorKept) {
  AppendUpTo(0, 2);
  const std::string committed = Lines();
  // A crash after one whole line and part of the next, before the summary was rewritten.
  const std::string whole_line = Lines().substr(0, Lines().find('\n') + 1);
  ASSERT_TRUE(WriteFileAtomically(Path("evaluations.jsonl"),
                                  committed + whole_line + "{\"step\": \"3")
                  .ok());
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(2));
  // The next append starts where the log ends: the file is as if there had been no crash.
  AppendUpTo(2, 3);
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(3));
  const std::string crashed = Lines();
  std::filesystem::remove_all(dir());
  std::filesystem::create_directories(dir());
  AppendUpTo(0, 2);
  AppendUpTo(2, 3);
  EXPECT_EQ(crashed, Lines());
}

TEST_F(AppendedEvaluationLogTest, EvaluationsSentAgainAreNotAppendedAgain) {
  AppendUpTo(0, 3);
  // A learner resumed from the checkpoint of the second evaluation makes the third again.
  ASSERT_TRUE(AppendEvaluationLog(Dir(), 2, EvaluationLogSince(LogOf(4, 0), 2)).ok());
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(4));
  // One that sends a checkpoint the log is past changes nothing.
  const std::string lines = Lines();
  AppendUpTo(0, 2);
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(4));
  EXPECT_EQ(Lines(), lines);
  // A learner from before evaluations_before sends the whole log: the same.
  AppendUpTo(0, 4);
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(4));
}

TEST_F(AppendedEvaluationLogTest, AGapIsRefusedAndTheLogKept) {
  AppendUpTo(0, 1);
  const absl::Status gap = AppendEvaluationLog(Dir(), 2, EvaluationLogSince(LogOf(3), 2));
  EXPECT_EQ(gap.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(gap.message(), HasSubstr("holds 1 evaluations; evaluations from number 3 on"));
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(1));
}

TEST_F(AppendedEvaluationLogTest, ALogOfAnOlderCoordinatorIsReadAndAppendedTo) {
  ASSERT_TRUE(WriteEvaluationLog(Dir(), LogOf(2)).ok());
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(2));
  AppendUpTo(2, 4);
  ExpectSameLog(ReadEvaluationLog(Dir()), LogOf(4));
  EXPECT_FALSE(std::filesystem::exists(Path("evaluations.json")));
  EXPECT_FALSE(std::filesystem::exists(Path("evaluations.csv")));
}

TEST_F(AppendedEvaluationLogTest, ADamagedLogIsDataLossNamingTheFileAndLine) {
  AppendUpTo(0, 3);
  const std::string lines = Lines();
  const size_t second = lines.find('\n') + 1;
  std::string damaged = lines;
  damaged[second] = 'x';
  ASSERT_TRUE(WriteFileAtomically(Path("evaluations.jsonl"), damaged).ok());
  absl::Status status = ReadEvaluationLog(Dir()).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr("evaluations.jsonl line 2 is not Evaluation"));

  // Shorter than its summary says: committed lines lost.
  ASSERT_TRUE(WriteFileAtomically(Path("evaluations.jsonl"), lines.substr(0, second)).ok());
  status = ReadEvaluationLog(Dir()).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr("the log has"));
}

}  // namespace
}  // namespace dcs::run
