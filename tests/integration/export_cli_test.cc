// Copyright 2026 The DCS Authors.
//
// `dcs export` as a user runs it: a trained run's policy becomes a state dict that PyTorch
// loads into Stable-Baselines3's layout and that acts as DCS does (tests/learner/export_check.h),
// with its observation layout beside it; a run that does not exist, a corrupt checkpoint and an
// --out where the layout would go are one error line each, and write nothing.

#include <filesystem>
#include <string>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/trained_policy.h"
#include "services/exit_codes.h"
#include "tests/integration/test_util.h"
#include "tests/learner/export_check.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using dcs::testing::MakeTempDir;
using ::testing::HasSubstr;
using ::testing::SizeIs;

RunResult Dcs(const std::vector<std::string>& args) { return RunProgram(BinaryPath("dcs"), args); }

// A tiny CartPole run observing its pole length, trained by `dcs train` into `dir`/run.
std::string TrainTinyRun(const std::string& dir) {
  const std::string config = dir + "/tiny.yaml";
  EXPECT_TRUE(WriteFileAtomically(config, R"(
env: cartpole
seed: 3
total_timesteps: 256
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
observe: live
evaluation: {freq: 256, episodes: 1, contexts: {id: [0.5]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)").ok());
  const std::string run = dir + "/run";
  const RunResult train = Dcs({"train", "--config", config, "--out", run});
  EXPECT_EQ(train.exit_code, 0) << train.output;
  return run;
}

TEST(ExportCliTest, WritesAStateDictThatActsAsDcsAndItsLayout) {
  const std::string dir = MakeTempDir();
  const std::string run = TrainTinyRun(dir);
  const std::string policy = dir + "/policy.pt";
  const RunResult exported = Dcs({"export", run, "--out", policy});
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_THAT(Lines(exported.output), SizeIs(1));
  EXPECT_THAT(exported.output,
              HasSubstr(absl::StrCat("wrote ", policy, " (MlpPolicy state dict) and ", dir,
                                     "/policy.json (observation layout)")));
  const std::string layout = ReadFile(dir + "/policy.json").value_or("");
  EXPECT_THAT(layout, HasSubstr(R"("observe_mode": "live")"));
  EXPECT_THAT(layout, HasSubstr(R"("name": "length")"));

  absl::StatusOr<learner::TrainedPolicy> trained = learner::LoadTrainedPolicy(run, "last");
  ASSERT_TRUE(trained.ok()) << trained.status();
  const std::string check_dir = dir + "/check";
  std::filesystem::create_directory(check_dir);
  const learner::ExportCheck check = learner::CheckExport(*trained, policy, check_dir);
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("1000 observations, agree"));
}

TEST(ExportCliTest, ARunThatDoesNotExistIsOneErrorLine) {
  const std::string dir = MakeTempDir();
  const RunResult exported = Dcs({"export", dir + "/no-such-run", "--out", dir + "/policy.pt"});
  EXPECT_NE(exported.exit_code, services::kExitOk);
  ASSERT_THAT(Lines(exported.output), SizeIs(1)) << exported.output;
  EXPECT_THAT(exported.output, HasSubstr("NOT_FOUND"));
  EXPECT_THAT(exported.output, HasSubstr("no-such-run"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/policy.pt"));
}

TEST(ExportCliTest, ACorruptCheckpointIsDataLossNamingTheFile) {
  const std::string dir = MakeTempDir();
  const std::string run = TrainTinyRun(dir);
  std::string learner_file;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(run + "/checkpoints")) {
    if (entry.path().filename() == "learner.bin") learner_file = entry.path().string();
  }
  ASSERT_FALSE(learner_file.empty());
  absl::StatusOr<std::string> bytes = ReadFile(learner_file);
  ASSERT_TRUE(bytes.ok()) << bytes.status();
  ASSERT_TRUE(WriteFileAtomically(learner_file, bytes->substr(0, bytes->size() / 2)).ok());

  const RunResult exported = Dcs({"export", run, "--out", dir + "/policy.pt"});
  EXPECT_NE(exported.exit_code, services::kExitOk);
  ASSERT_THAT(Lines(exported.output), SizeIs(1)) << exported.output;
  EXPECT_THAT(exported.output, HasSubstr("DATA_LOSS"));
  EXPECT_THAT(exported.output, HasSubstr(learner_file));
  EXPECT_FALSE(std::filesystem::exists(dir + "/policy.pt"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/policy.json"));
}

TEST(ExportCliTest, AnOutEndingInJsonIsRefused) {
  const std::string dir = MakeTempDir();
  const RunResult exported = Dcs({"export", dir, "--out", dir + "/policy.json"});
  EXPECT_EQ(exported.exit_code, services::kExitDataError) << exported.output;
  EXPECT_THAT(exported.output, HasSubstr("where the observation layout goes"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/policy.json"));
}

}  // namespace
}  // namespace dcs::integration
