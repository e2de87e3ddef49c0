// Copyright 2026 The DCS Authors.
//
// `dcs train` as a user runs it: a run writes its directory and summary; a second run into the
// same directory is refused; Ctrl-C stops with a checkpoint that --resume continues; a bad
// config is one error line naming the field, and a config with several problems lists them all.

#include <signal.h>
#include <sys/wait.h>

#include <filesystem>
#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "dcs/v1/evaluation.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "services/cli/child_process.h"
#include "services/exit_codes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/scoped_variable.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

using dcs::testing::MakeTempDir;
using dcs::testing::ScopedVariable;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::SizeIs;

RunResult Dcs(const std::vector<std::string>& args) { return RunProgram(BinaryPath("dcs"), args); }

// A CartPole run of `total` steps in 64-step rollouts, evaluated every 256 steps.
std::string WriteConfig(const std::string& dir, int total) {
  const std::string path = absl::StrCat(dir, "/tiny.yaml");
  EXPECT_TRUE(WriteFileAtomically(path, absl::StrCat(R"(
env: cartpole
seed: 5
total_timesteps: )", total, R"(
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
evaluation: {freq: 256, episodes: 2, contexts: {id: [0.5], ood_high: [1.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)")).ok());
  return path;
}

v1::EvaluationLog ReadLog(const std::string& run_dir) {
  absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(run_dir);
  EXPECT_TRUE(log.ok()) << log.status();
  return log.value_or(v1::EvaluationLog());
}

TEST(TrainCliTest, TrainsIntoItsDirectoryAndRefusesToOverwriteIt) {
  const std::string dir = MakeTempDir();
  const std::string config = WriteConfig(dir, 1024);
  const std::string out = dir + "/run";
  const RunResult train = Dcs({"train", "--config", config, "--out", out});
  ASSERT_EQ(train.exit_code, 0) << train.output;
  EXPECT_THAT(train.output, HasSubstr("last          avg_combined"));
  EXPECT_THAT(train.output, HasSubstr("best-anytime  avg_combined"));
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    EXPECT_THAT(train.output, ContainsRegex("kernels +libtorch [0-9.]+, openblas Haswell, "
                                            "aten avx2"));
  }
  const v1::EvaluationLog log = ReadLog(out);
  EXPECT_TRUE(log.complete());
  EXPECT_THAT(log.evaluations(), SizeIs(5));  // 256, 512, 768, 1024 and the end
  EXPECT_TRUE(std::filesystem::exists(out + "/evaluations.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/checkpoints/latest"));
  EXPECT_EQ(ReadFile(out + "/config.yaml").value_or(""), ReadFile(config).value_or("-"));

  const RunResult again = Dcs({"train", "--config", config, "--out", out});
  EXPECT_EQ(again.exit_code, services::kExitFailure);
  ASSERT_THAT(Lines(again.output), SizeIs(1)) << again.output;
  EXPECT_THAT(again.output, HasSubstr("already holds a run: pass --resume"));
}

TEST(TrainCliTest, SeedFlagOverridesTheConfigAndNamesTheDefaultDirectory) {
  const std::string dir = MakeTempDir();
  const std::string config = WriteConfig(dir, 128);
  const RunResult train = Dcs({"train", "--config", config, "--seed", "7", "--data-dir", dir});
  ASSERT_EQ(train.exit_code, 0) << train.output;
  const std::string out = dir + "/runs/tiny-seed7";
  EXPECT_EQ(ReadLog(out).seed(), 7u);
  EXPECT_THAT(ReadFile(out + "/config.yaml").value_or(""), HasSubstr("seed: 7"));
}

TEST(TrainCliTest, CtrlCStopsWithACheckpointThatResumeContinues) {
  const std::string dir = MakeTempDir();
  const std::string config = WriteConfig(dir, 64 * 1000);
  const std::string out = dir + "/run";
  const std::string output = dir + "/train.log";
  absl::StatusOr<services::cli::ChildProcess> train = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs"),
       .args = {"train", "--config", config, "--out", out},
       .output_path = output});
  ASSERT_TRUE(train.ok()) << train.status();
  // Off a terminal, progress is a line per evaluation.
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
  while (absl::Now() < deadline &&
         ReadFile(output).value_or("").find("eval@") == std::string::npos) {
    absl::SleepFor(absl::Milliseconds(10));
  }
  ::kill(train->pid(), SIGINT);
  std::optional<int> status = train->Wait(testing::Patient(absl::Seconds(30)));
  ASSERT_TRUE(status.has_value()) << "dcs train did not stop";
  const std::string log = ReadFile(output).value_or("");
  ASSERT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == services::kExitInterrupted)
      << services::cli::DescribeExit(*status) << "\n" << log;
  EXPECT_THAT(log, HasSubstr(absl::StrCat("continue with: dcs train --resume --out ", out)));
  EXPECT_FALSE(ReadLog(out).complete());

  const RunResult resume = Dcs({"train", "--resume", "--out", out});
  ASSERT_EQ(resume.exit_code, 0) << resume.output;
  const v1::EvaluationLog finished = ReadLog(out);
  EXPECT_TRUE(finished.complete());
  EXPECT_EQ(finished.evaluations(finished.evaluations_size() - 1).updates(), 1000);
}

// `dcs train` hands the run to dcs-train with the pinned numeric kernels in its environment
// (common/pinned_kernels.h), over a user's own choice, so libtorch starts once: dcs-train has
// nothing to restart for.
TEST(TrainCliTest, HandsOverWithThePinnedKernelsSoLibtorchStartsOnce) {
  const std::string dir = MakeTempDir();
  const std::string config = WriteConfig(dir, 128);
  ScopedVariable blas("OPENBLAS_CORETYPE", "Prescott");
  ScopedVariable aten("ATEN_CPU_CAPABILITY", std::nullopt);
  const LoaderReport loader;
  const RunResult train = Dcs({"train", "--config", config, "--out", dir + "/run"});
  ASSERT_EQ(train.exit_code, 0) << train.output;
  EXPECT_EQ(loader.LibtorchStarts(), 1);
  EXPECT_THAT(train.output, ContainsRegex("kernels +libtorch [0-9.]+, openblas Haswell, "
                                          "aten avx2"));
}

// dcs-train started by hand without the pinned kernels runs itself again with them, silently
// (learner::PinNumericKernels): the fallback for a trainer DCS did not start.
TEST(TrainCliTest, DcsTrainStartedWithOtherKernelsRunsItselfAgainWithThePinnedOnes) {
  const std::string dir = MakeTempDir();
  const std::string config = WriteConfig(dir, 128);
  ScopedVariable blas("OPENBLAS_CORETYPE", "Prescott");
  ScopedVariable threads("OPENBLAS_NUM_THREADS", "2");
  ScopedVariable aten("ATEN_CPU_CAPABILITY", "default");
  const LoaderReport loader;
  const RunResult train =
      RunProgram(BinaryPath("dcs-train"), {"train", "--config", config, "--out", dir + "/run"});
  ASSERT_EQ(train.exit_code, 0) << train.output;
  EXPECT_EQ(loader.LibtorchStarts(), 2);
  EXPECT_THAT(train.output, Not(HasSubstr("will not match other machines")));  // silently
  EXPECT_THAT(train.output, ContainsRegex("kernels +libtorch [0-9.]+, openblas Haswell, "
                                          "aten avx2"));
}

TEST(TrainCliTest, BadConfigIsOneErrorLineNamingTheField) {
  const std::string dir = MakeTempDir();
  const std::string config = absl::StrCat(dir, "/bad.yaml");
  ASSERT_TRUE(WriteFileAtomically(config, "env: cartpole\nppo: {learning_rat: 0.1}\n").ok());
  RunResult train = Dcs({"train", "--config", config, "--out", dir + "/run"});
  EXPECT_EQ(train.exit_code, services::kExitDataError);
  ASSERT_THAT(Lines(train.output), SizeIs(1)) << train.output;
  EXPECT_THAT(train.output, HasSubstr("ppo.learning_rat"));
  EXPECT_THAT(train.output, HasSubstr("line 2"));

  ASSERT_TRUE(WriteFileAtomically(config, R"(
env: cartpole
evaluation: {contexts: {id: [0.5], ood_high: [1.0, 9.0]}}
)").ok());
  train = Dcs({"train", "--config", config, "--out", dir + "/run"});
  EXPECT_EQ(train.exit_code, services::kExitDataError);
  EXPECT_THAT(train.output, HasSubstr("evaluation.contexts.ood_high[1]"));

  train = Dcs({"train", "--config", dir + "/missing.yaml"});
  EXPECT_EQ(train.exit_code, services::kExitNoInput);
  EXPECT_THAT(train.output, HasSubstr("cannot read the run config"));
}

// Issue 35: a bad learning rate, amplitude and period are named together, each with its path
// and line, as a sweep spec's problems are; nothing is trained.
TEST(TrainCliTest, BadConfigListsEveryProblemWithItsPathAndLine) {
  const std::string dir = MakeTempDir();
  const std::string config = absl::StrCat(dir, "/bad.yaml");
  ASSERT_TRUE(WriteFileAtomically(config, R"(env: cartpole
feature: length
training_range: [0.35, 0.75]
schedule: {family: sinusoidal, amplitude_frac: -0.5, period: -3}
evaluation: {contexts: {id: [0.5]}}
ppo: {learning_rate: -1}
)").ok());
  const RunResult train = Dcs({"train", "--config", config, "--out", dir + "/run"});
  EXPECT_EQ(train.exit_code, services::kExitDataError);
  EXPECT_THAT(train.output, HasSubstr(absl::StrCat("3 problems in ", config, ":\n")));
  EXPECT_THAT(train.output, HasSubstr(absl::StrCat(config, ": schedule.amplitude_frac: line 4: ")));
  EXPECT_THAT(train.output, HasSubstr(absl::StrCat(config, ": schedule.period: line 4: ")));
  EXPECT_THAT(train.output, HasSubstr(absl::StrCat(config, ": ppo.learning_rate: line 6: ")));
  EXPECT_FALSE(std::filesystem::exists(dir + "/run"));
}

}  // namespace
}  // namespace dcs::integration
