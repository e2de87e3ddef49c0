// Copyright 2026 The DCS Authors.
#include "run/evaluation_log.h"

#include <cmath>
#include <string>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "common/atomic_file.h"
#include "common/enum_names.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

actor::EvaluationResult Evaluation(int64_t step, double id_return, double ood_return) {
  actor::EvaluationResult evaluation{
      .step = step,
      .updates = step / 100,
      .contexts = {{.context = {.split = actor::Split::kId, .value = 0.5},
                    .returns = {id_return, id_return + 2}},
                   {.context = {.split = actor::Split::kOodHigh, .value = 1.0},
                    .returns = {ood_return}}}};
  actor::Summarize(evaluation);
  return evaluation;
}

RunSpec Spec() {
  RunSpec spec;
  spec.seed = 9;
  return spec;
}

TEST(EvaluationLogTest, ReadsBackWhatWasWritten) {
  const std::string dir = testing::MakeTempDir();
  const v1::EvaluationLog log = MakeEvaluationLog(
      Spec(), {Evaluation(100, 10, 4), Evaluation(200, 30, 2), Evaluation(250, 20, 0)}, {},
      /*complete=*/true);
  ASSERT_TRUE(WriteEvaluationLog(dir, log).ok());
  absl::StatusOr<v1::EvaluationLog> read = ReadEvaluationLog(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->SerializeAsString(), log.SerializeAsString());
  EXPECT_EQ(read->seed(), 9u);
  EXPECT_EQ(read->last(), (21.0 + 0) / 2);
  EXPECT_EQ(read->best_anytime_index(), 1);
  EXPECT_EQ(read->evaluations(0).contexts(1).split(), v1::SPLIT_OOD_HIGH);
  EXPECT_EQ(EvaluationCsvPath(dir), dir + "/evaluations.csv");
  EXPECT_THAT(ReadFile(EvaluationCsvPath(dir)).value_or(""),
              HasSubstr("\n100,1,ood_high,1,1,4,0,0\n"));
}

TEST(EvaluationLogTest, MultiStageBestAnytimeIsAtBoundariesAndTheEnd) {
  const v1::EvaluationLog log = MakeEvaluationLog(
      Spec(), {Evaluation(100, 90, 90), Evaluation(200, 30, 2), Evaluation(250, 20, 0)}, {200},
      /*complete=*/true);
  EXPECT_EQ(log.best_anytime_index(), 1);
}

TEST(EvaluationLogTest, ReadingRefusesWhatIsNotAnEvaluationLog) {
  const std::string dir = testing::MakeTempDir();
  EXPECT_EQ(ReadEvaluationLog(dir).status().code(), absl::StatusCode::kNotFound);

  ASSERT_TRUE(WriteFileAtomically(dir + "/evaluations.json", "{\"seed\": ").ok());
  absl::Status status = ReadEvaluationLog(dir).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr(dir + "/evaluations.json is not an evaluation log"));

  // A split no evaluation has: once silently read as ID.
  ASSERT_TRUE(WriteEvaluationLog(dir, MakeEvaluationLog(Spec(), {Evaluation(100, 1, 2)}, {},
                                                        /*complete=*/false))
                  .ok());
  const std::string json = ReadFile(dir + "/evaluations.json").value_or("");
  ASSERT_THAT(json, HasSubstr("\"SPLIT_OOD_HIGH\""));
  ASSERT_TRUE(
      WriteFileAtomically(dir + "/evaluations.json",
                          absl::StrReplaceAll(json, {{"\"SPLIT_OOD_HIGH\"", "7"}}))
          .ok());
  status = ReadEvaluationLog(dir).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr("has a context of split 7, which is none of id, "
                                          "ood_low or ood_high"));
}

TEST(EvaluationLogTest, SplitNamesAgreeWithTheProtoEnumeration) {
  for (const auto& [split, name] : actor::kSplitNames) {
    const v1::Split proto = SplitToProto(split);
    EXPECT_EQ(v1::Split_Name(proto), absl::StrCat("SPLIT_", absl::AsciiStrToUpper(name)));
    EXPECT_EQ(SplitFromProto(proto), split);
  }
  EXPECT_EQ(SplitFromProto(v1::SPLIT_UNSPECIFIED), std::nullopt);
  EXPECT_EQ(SplitFromProto(v1::Split_ARRAYSIZE), std::nullopt);
}

}  // namespace
}  // namespace dcs::run
