// Copyright 2026 The DCS Authors.
#include "run/run_checkpoint.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <string>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::run {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

RunState StateAt(int64_t timesteps) {
  actor::EvaluationResult evaluation{
      .step = timesteps,
      .updates = timesteps / 64,
      .contexts = {{.context = {.split = actor::Split::kOodHigh, .value = 0.1 + 0.2},
                    .returns = {1.0 / 3, 500},
                    .seconds = 0.25}}};
  actor::Summarize(evaluation);
  return {.timesteps = timesteps,
          .rollouts = timesteps / 64,
          .journals = {{.episode = 7, .reset_step = timesteps - 3, .actions = {1, 0, 1},
                        .episode_return = 3},
                       {.episode = 4, .reset_step = timesteps}},
          .recent_returns = {12.5, 1e-17},
          .recent_lengths = {13, 2},
          .evaluations = {evaluation}};
}

std::vector<std::string> CheckpointNames(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(dir) / "checkpoints")) {
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void Overwrite(const fs::path& path, absl::string_view contents) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << contents;
}

TEST(RunCheckpointTest, ReadsBackExactlyWhatWasWritten) {
  const std::string dir = testing::MakeTempDir();
  const RunState state = StateAt(128);
  ASSERT_TRUE(WriteCheckpoint(dir, state, std::string("learner\0bytes", 13), 3).ok());
  absl::StatusOr<Checkpoint> read = ReadLatestCheckpoint(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->name, "000000000128");
  EXPECT_EQ(read->learner, std::string("learner\0bytes", 13));
  EXPECT_EQ(read->state.timesteps, 128);
  EXPECT_EQ(read->state.rollouts, 2);
  EXPECT_EQ(read->state.recent_returns, state.recent_returns);
  EXPECT_THAT(read->state.recent_lengths, ElementsAre(13, 2));
  ASSERT_EQ(read->state.journals.size(), 2u);
  EXPECT_EQ(read->state.journals[0].episode, 7);
  EXPECT_EQ(read->state.journals[0].reset_step, 125);
  EXPECT_THAT(read->state.journals[0].actions, ElementsAre(1, 0, 1));
  EXPECT_TRUE(read->state.journals[1].actions.empty());
  ASSERT_EQ(read->state.evaluations.size(), 1u);
  const actor::EvaluationResult& evaluation = read->state.evaluations[0];
  EXPECT_EQ(evaluation.updates, 2);
  EXPECT_EQ(evaluation.contexts[0].context.split, actor::Split::kOodHigh);
  EXPECT_EQ(evaluation.contexts[0].context.value, 0.1 + 0.2);  // bit for bit
  EXPECT_EQ(evaluation.contexts[0].returns, state.evaluations[0].contexts[0].returns);
  EXPECT_EQ(evaluation.avg_combined, state.evaluations[0].avg_combined);
}

// The decoder reads YAML's .inf and .nan, so the encoder must write them so: a run state that
// decodes must encode to one that decodes to it again (found by tests/fuzz/checkpoint_fuzzer).
TEST(RunCheckpointTest, NonFiniteValuesReadBackAsThemselves) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  RunState state = StateAt(64);
  state.recent_returns = {kInf, -kInf, std::numeric_limits<double>::quiet_NaN()};
  state.journals[0].actions = {0, std::numeric_limits<float>::infinity()};
  state.journals[0].episode_return = -kInf;
  state.evaluations[0].contexts[0].seconds = kInf;
  const std::string text = EncodeRunState(state);
  absl::StatusOr<RunState> read = DecodeRunState(text, "run.yaml");
  ASSERT_TRUE(read.ok()) << read.status() << "\n" << text;
  EXPECT_EQ(read->recent_returns[0], kInf);
  EXPECT_EQ(read->recent_returns[1], -kInf);
  EXPECT_TRUE(std::isnan(read->recent_returns[2]));
  EXPECT_THAT(read->journals[0].actions, ElementsAre(0, std::numeric_limits<float>::infinity()));
  EXPECT_EQ(read->journals[0].episode_return, -kInf);
  EXPECT_EQ(read->evaluations[0].contexts[0].seconds, kInf);
  EXPECT_EQ(EncodeRunState(*read), text);
}

TEST(RunCheckpointTest, KeepsTheNewestAndPointsLatestAtIt) {
  const std::string dir = testing::MakeTempDir();
  for (int64_t t : {64, 128, 192, 256}) ASSERT_TRUE(WriteCheckpoint(dir, StateAt(t), "x", 2).ok());
  EXPECT_THAT(CheckpointNames(dir), ElementsAre("000000000192", "000000000256"));
  EXPECT_EQ(*ReadFile(dir + "/checkpoints/latest"), "000000000256\n");
}

TEST(RunCheckpointTest, CorruptNewestFallsBackToThePreviousOne) {
  const std::string dir = testing::MakeTempDir();
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(64), "old learner", 3).ok());
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(128), "new learner", 3).ok());
  const fs::path newest = fs::path(dir) / "checkpoints" / "000000000128";

  Overwrite(newest / "learner.bin", "new learneR");  // a flipped byte
  absl::StatusOr<Checkpoint> read = ReadLatestCheckpoint(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->state.timesteps, 64);
  EXPECT_EQ(read->learner, "old learner");

  // A run.yaml cut at a line boundary still parses: the manifest catches it.
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(128), "new learner", 3).ok());
  const std::string yaml = *ReadFile((newest / "run.yaml").string());
  Overwrite(newest / "run.yaml", yaml.substr(0, yaml.find("evaluations:")));
  read = ReadLatestCheckpoint(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->state.timesteps, 64);
}

TEST(RunCheckpointTest, NewerCheckpointThatLatestDoesNotNameIsIgnored) {
  const std::string dir = testing::MakeTempDir();
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(64), "a", 3).ok());
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(128), "b", 3).ok());
  // As if the writer died before moving the pointer.
  Overwrite(fs::path(dir) / "checkpoints" / "latest", "000000000064\n");
  absl::StatusOr<Checkpoint> read = ReadLatestCheckpoint(dir);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(read->state.timesteps, 64);
}

TEST(RunCheckpointTest, NoneOrOnlyCorruptCheckpointsAreErrors) {
  const std::string dir = testing::MakeTempDir();
  EXPECT_EQ(ReadLatestCheckpoint(dir).status().code(), absl::StatusCode::kNotFound);
  ASSERT_TRUE(WriteCheckpoint(dir, StateAt(64), "learner", 3).ok());
  Overwrite(fs::path(dir) / "checkpoints" / "000000000064" / "learner.bin", "");
  const absl::Status status = ReadLatestCheckpoint(dir).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(status.message(), HasSubstr("learner.bin does not match"));
}

}  // namespace
}  // namespace dcs::run
