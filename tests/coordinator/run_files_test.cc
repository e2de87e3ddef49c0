// Copyright 2026 The DCS Authors.
#include "coordinator/run_files.h"

#include <filesystem>
#include <cmath>
#include <map>
#include <optional>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/appended_evaluation_log.h"
#include "run/evaluation_log.h"
#include "run/run_checkpoint.h"
#include "tests/testing/temp_dir.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::Field;
using ::testing::HasSubstr;

run::PackedCheckpoint Arriving(int64_t timesteps) {
  return run::PackCheckpoint(
      {.name = run::CheckpointName(timesteps),
       .state = {.timesteps = timesteps, .rollouts = 2, .journals = {{.episode = 3}}},
       .learner = "learner bytes"});
}

v1::EvaluationLog Log() {
  v1::EvaluationLog log;
  log.set_env("cartpole");
  return log;
}

class RunFilesTest : public testing::TempDirTest {};

TEST_F(RunFilesTest, StoresACheckpointAsDcsTrainLaysItOut) {
  const std::string run_dir = RunDirectory(dir().string(), "run-1");
  EXPECT_EQ(run_dir, (dir() / "runs" / "run-1").string());
  ASSERT_TRUE(StoreCheckpoint(run_dir, Arriving(256), 0, Log(), 3).ok());
  absl::StatusOr<run::PackedCheckpoint> latest = LatestCheckpoint(run_dir);
  ASSERT_TRUE(latest.ok()) << latest.status();
  EXPECT_EQ(latest->name, "000000000256");
  EXPECT_EQ(latest->learner, "learner bytes");
  EXPECT_EQ(latest->run_state_sha256, Arriving(256).run_state_sha256);
  absl::StatusOr<std::vector<RunFile>> files = ReadRunFiles(run_dir);
  ASSERT_TRUE(files.ok());
  EXPECT_THAT(*files, ElementsAre(Field(&RunFile::path, "checkpoints/000000000256/MANIFEST"),
                                  Field(&RunFile::path, "checkpoints/000000000256/learner.bin"),
                                  Field(&RunFile::path, "checkpoints/000000000256/run.yaml"),
                                  Field(&RunFile::path, "checkpoints/latest"),
                                  Field(&RunFile::path, "evaluations.csv"),
                                  Field(&RunFile::path, "evaluations.json")));
}

TEST_F(RunFilesTest, HandsOutTheAppendedLogAsDcsTrainWritesIt) {
  const std::string run_dir = RunDirectory(dir().string(), "run-1");
  v1::EvaluationLog log = Log();
  log.add_evaluations()->set_step(128);
  ASSERT_TRUE(StoreCheckpoint(run_dir, Arriving(128), 0, log, 3).ok());
  log.add_evaluations()->set_step(256);
  log.set_complete(true);
  ASSERT_TRUE(StoreCheckpoint(run_dir, Arriving(256), 1, run::EvaluationLogSince(log, 1), 3).ok());
  absl::StatusOr<std::vector<RunFile>> files = ReadRunFiles(run_dir);
  ASSERT_TRUE(files.ok()) << files.status();
  std::map<std::string, std::string> contents;
  for (const RunFile& file : *files) contents[file.path] = file.contents;
  EXPECT_FALSE(contents.contains("evaluations.jsonl"));
  for (const run::EvaluationLogFile& file : run::EvaluationLogFiles(log)) {
    EXPECT_EQ(contents[file.name], file.contents) << file.name;
  }
}

TEST_F(RunFilesTest, RefusesACorruptCheckpointAndStoresNothing) {
  const std::string run_dir = RunDirectory(dir().string(), "run-1");
  run::PackedCheckpoint corrupt = Arriving(256);
  corrupt.learner[0] = 'L';
  const absl::Status status = StoreCheckpoint(run_dir, corrupt, 0, Log(), 3).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr("learner.bin of checkpoint 000000000256 arrived corrupt"));
  EXPECT_EQ(LatestCheckpoint(run_dir).status().code(), absl::StatusCode::kNotFound);

  // The name becomes a directory: only a step's name is taken.
  for (const char* name : {"../../escape", "latest", "256", "00000000025x"}) {
    run::PackedCheckpoint misnamed = Arriving(256);
    misnamed.name = name;
    const absl::Status refused = StoreCheckpoint(run_dir, misnamed, 0, Log(), 3).status();
    EXPECT_EQ(refused.code(), absl::StatusCode::kInvalidArgument) << name;
    EXPECT_THAT(refused.message(), HasSubstr("is not a checkpoint's name")) << name;
  }
  EXPECT_EQ(LatestCheckpoint(run_dir).status().code(), absl::StatusCode::kNotFound);
}

TEST_F(RunFilesTest, AMissingRunHasNoFiles) {
  EXPECT_EQ(ReadRunFiles(RunDirectory(dir().string(), "run-9")).status().code(),
            absl::StatusCode::kNotFound);
}

TEST(ScoreEvaluationsTest, TheLatestIsTheHighestStepAndTheBestTheFirstHighestScore) {
  EXPECT_EQ(ScoreEvaluations(v1::EvaluationLog()), std::nullopt);
  v1::EvaluationLog log;
  for (const auto& [step, score] :
       {std::pair(512, 7.0), std::pair(256, 9.0), std::pair(768, 9.0), std::pair(1024, 3.0)}) {
    v1::Evaluation& evaluation = *log.add_evaluations();
    evaluation.set_step(step);
    evaluation.set_avg_combined(score);
    evaluation.mutable_id()->set_mean(score + 1);
    evaluation.mutable_ood_low()->set_mean(score + 2);
    evaluation.mutable_ood_high()->set_mean(score + 3);
  }
  const std::optional<EvaluationScores> scores = ScoreEvaluations(log);
  ASSERT_TRUE(scores.has_value());
  EXPECT_EQ(scores->latest_step, 1024);
  EXPECT_EQ(scores->latest_avg_combined, 3);
  EXPECT_EQ(scores->latest_id_return, 4);
  EXPECT_EQ(scores->latest_ood_low_return, 5);
  EXPECT_EQ(scores->latest_ood_high_return, 6);
  EXPECT_EQ(scores->best_step, 256);
  EXPECT_EQ(scores->best_avg_combined, 9);

  log.mutable_evaluations(1)->set_avg_combined(std::nan(""));  // NaN is never the best
  EXPECT_EQ(ScoreEvaluations(log)->best_step, 768);
}

TEST(DiskSpaceTest, MeasuresTheDataDirectorysFileSystemAndNamesAMissingOne) {
  const std::string dir = testing::MakeTempDir();
  absl::StatusOr<DiskSpace> space = DiskSpaceOf(dir);
  ASSERT_TRUE(space.ok()) << space.status();
  EXPECT_GT(space->capacity_bytes, 0);
  EXPECT_LE(space->free_bytes, space->capacity_bytes);
  const absl::StatusOr<DiskSpace> missing = DiskSpaceOf(dir + "/missing");
  EXPECT_EQ(missing.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr("missing"));
}

}  // namespace
}  // namespace dcs::coordinator
