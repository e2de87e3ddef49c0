// Copyright 2026 The DCS Authors.
//
// The `dcs` client as a user runs it: up (detached and in the foreground), status, health,
// down, version, --help; Ctrl-C and a dying process leave nothing behind.

#include <signal.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/pinned_kernels.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/local_cluster.h"
#include "services/exit_codes.h"
#include "tests/integration/test_util.h"
#include "tests/testing/net.h"
#include "tests/testing/scoped_variable.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

using dcs::testing::MakeTempDir;
using dcs::testing::PickFreePort;
using dcs::testing::ScopedVariable;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::SizeIs;

RunResult Dcs(const std::vector<std::string>& args) { return RunProgram(BinaryPath("dcs"), args); }

void ExpectAllStopped(const services::cli::ClusterState& state) {
  for (const services::cli::ClusterProcess& process : state.processes) {
    EXPECT_FALSE(services::cli::IsProcessRunning(process.pid, process.executable)) << process.name;
  }
}

// Starts `dcs up` in the foreground and waits until it reports the cluster up.
struct ForegroundUp {
  services::cli::ChildProcess dcs;
  std::string output_path;
  services::cli::ClusterState state;
};
std::optional<ForegroundUp> StartForegroundUp(const std::string& data_dir) {
  const std::string output = absl::StrCat(MakeTempDir(), "/up.log");
  absl::StatusOr<services::cli::ChildProcess> dcs = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs"),
       .args = {"up", "--actors=2", absl::StrCat("--data-dir=", data_dir)},
       .output_path = output});
  EXPECT_TRUE(dcs.ok()) << dcs.status();
  if (!dcs.ok()) return std::nullopt;
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
  while (absl::Now() < deadline) {
    if (ReadFile(output).value_or("").find("press Ctrl-C") != std::string::npos) {
      absl::StatusOr<services::cli::ClusterState> state = services::cli::ReadClusterState(data_dir);
      EXPECT_TRUE(state.ok()) << state.status();
      if (!state.ok()) return std::nullopt;
      return ForegroundUp{*std::move(dcs), output, *std::move(state)};
    }
    absl::SleepFor(absl::Milliseconds(50));
  }
  ADD_FAILURE() << "dcs up did not come up: " << ReadFile(output).value_or("");
  return std::nullopt;
}

TEST(DcsCliTest, UpDetachedThenStatusThenDown) {
  const std::string data_dir = MakeTempDir();
  const RunResult up = Dcs({"up", "--detach", "--actors=2", "--data-dir", data_dir});
  ASSERT_EQ(up.exit_code, 0) << up.output;
  absl::StatusOr<services::cli::ClusterState> state = services::cli::ReadClusterState(data_dir);
  ASSERT_TRUE(state.ok()) << state.status();
  ASSERT_THAT(state->processes, SizeIs(4));
  // `dcs up` made the cluster a token, readable by its owner only; `dcs status` below calls
  // the coordinator with it.
  const std::filesystem::path token = services::cli::TokenPath(data_dir);
  ASSERT_TRUE(std::filesystem::exists(token));
  EXPECT_EQ(std::filesystem::status(token).permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);

  const RunResult status = Dcs({"status", "--data-dir", data_dir});
  EXPECT_EQ(status.exit_code, 0) << status.output;
  EXPECT_THAT(status.output, HasSubstr(state->coordinator_address));
  for (size_t i = 1; i < state->processes.size(); ++i) {
    EXPECT_THAT(status.output, HasSubstr(state->processes[i].grpc_address));
  }

  const RunResult json = Dcs({"status", "-o", "json", "--data-dir", data_dir});
  ASSERT_EQ(json.exit_code, 0) << json.output;
  google::protobuf::Struct parsed;  // states as words: not protobuf's own mapping
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(json.output, &parsed).ok())
      << json.output;
  const google::protobuf::ListValue& workers = parsed.fields().at("workers").list_value();
  ASSERT_THAT(workers.values(), SizeIs(3));
  for (const google::protobuf::Value& worker : workers.values()) {
    EXPECT_EQ(worker.struct_value().fields().at("state").string_value(), "alive") << json.output;
  }

  const RunResult health = Dcs({"health", "--addr", state->coordinator_address});
  EXPECT_EQ(health.exit_code, 0) << health.output;
  EXPECT_THAT(health.output, HasSubstr("SERVING"));

  const RunResult again = Dcs({"up", "--detach", "--data-dir", data_dir});
  EXPECT_EQ(again.exit_code, services::kExitFailure);
  EXPECT_THAT(again.output, HasSubstr("already runs"));

  const RunResult down = Dcs({"down", "--data-dir", data_dir});
  EXPECT_EQ(down.exit_code, 0) << down.output;
  ExpectAllStopped(*state);
  EXPECT_FALSE(std::filesystem::exists(absl::StrCat(data_dir, "/cluster.yaml")));
  EXPECT_FALSE(std::filesystem::exists(absl::StrCat(data_dir, "/prometheus-targets.yml")));
  EXPECT_FALSE(std::filesystem::exists(token));
}

// `dcs` in a directory, as a shell started there runs it.
RunResult DcsIn(const std::string& directory, const std::string& args) {
  return RunProgram("/bin/sh",
                    {"-c", absl::StrCat("cd '", directory, "' && exec '", BinaryPath("dcs"),
                                        "' ", args)});
}

TEST(DcsCliTest, TheLocalClusterIsFoundFromAnyDirectoryBelowItsDataDirectory) {
  const std::string project = MakeTempDir();
  const std::string data_dir = absl::StrCat(project, "/dcs-data");
  const std::string deep = absl::StrCat(project, "/configs/mine");
  std::filesystem::create_directories(deep);
  ASSERT_EQ(DcsIn(project, "up --detach --actors=1").exit_code, 0);
  absl::StatusOr<services::cli::ClusterState> state = services::cli::ReadClusterState(data_dir);
  ASSERT_TRUE(state.ok()) << state.status();

  // Two directories down, with neither --data-dir nor --addr: the cluster above, and its token.
  const RunResult status = DcsIn(deep, "status");
  EXPECT_EQ(status.exit_code, 0) << status.output;
  EXPECT_THAT(status.output, HasSubstr(state->coordinator_address));
  {
    // Anywhere else, DCS_DATA_DIR names it.
    ScopedVariable named("DCS_DATA_DIR", data_dir);
    const RunResult elsewhere = DcsIn(MakeTempDir(), "status");
    EXPECT_EQ(elsewhere.exit_code, 0) << elsewhere.output;
    EXPECT_THAT(elsewhere.output, HasSubstr(state->coordinator_address));
  }
  const RunResult down = DcsIn(deep, "down");
  EXPECT_EQ(down.exit_code, 0) << down.output;
  ExpectAllStopped(*state);
}

// Nothing listens on the default address (127.0.0.1:50051) on a test machine.
TEST(DcsCliTest, WithNoClusterFoundAnUnansweredCallSaysHowToStartOne) {
  const RunResult status = DcsIn(MakeTempDir(), "status --timeout=2s");
  EXPECT_EQ(status.exit_code, services::kExitUnavailable) << status.output;
  ASSERT_THAT(Lines(status.output), SizeIs(1)) << status.output;
  EXPECT_THAT(status.output, HasSubstr("no local cluster is recorded in dcs-data (looked here "
                                       "and in the parent directories): start one with `dcs up`"));
}

TEST(DcsCliTest, ADryRunChecksASpecWithNoClusterAndQueuesNothing) {
  const RunResult dry =
      DcsIn(MakeTempDir(), absl::StrCat("submit ", DCS_SOURCE_DIR, "/configs/quickstart.yaml",
                                        " --dry-run --timeout=1s"));
  EXPECT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_THAT(dry.output, HasSubstr("quickstart: 6 trials x 3 seeds = 18 runs"));
  EXPECT_THAT(dry.output, HasSubstr("sinusoidal"));
}

TEST(DcsCliTest, LogsListsPrintsTheLastLinesAndFollowsAProcesssLog) {
  const std::string data_dir = MakeTempDir();
  std::filesystem::create_directories(absl::StrCat(data_dir, "/logs"));
  const std::string coordinator_log = services::cli::ProcessLogPath(data_dir, "coordinator");
  ASSERT_TRUE(WriteFileAtomically(coordinator_log, "one\ntwo\nthree\n").ok());
  ASSERT_TRUE(
      WriteFileAtomically(services::cli::ProcessLogPath(data_dir, "learner"), "l\n").ok());

  const RunResult list = Dcs({"logs", "--data-dir", data_dir});
  EXPECT_EQ(list.exit_code, 0) << list.output;
  EXPECT_THAT(list.output, HasSubstr("coordinator"));
  EXPECT_THAT(list.output, HasSubstr("learner"));

  const RunResult last = Dcs({"logs", "coordinator", "-n", "2", "--data-dir", data_dir});
  EXPECT_EQ(last.exit_code, 0) << last.output;
  EXPECT_EQ(last.output, "two\nthree\n");

  const RunResult typo = Dcs({"logs", "learnr", "--data-dir", data_dir});
  EXPECT_EQ(typo.exit_code, services::kExitNoInput) << typo.output;
  EXPECT_THAT(typo.output, HasSubstr("did you mean learner?"));

  // -f prints what the process writes next.
  const std::string followed = absl::StrCat(MakeTempDir(), "/followed.txt");
  absl::StatusOr<services::cli::ChildProcess> follow = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs"),
       .args = {"logs", "coordinator", "-n", "0", "-f", "--data-dir", data_dir},
       .output_path = followed});
  ASSERT_TRUE(follow.ok()) << follow.status();
  absl::SleepFor(absl::Milliseconds(300));  // it printed nothing (-n 0) and follows
  {
    std::ofstream append(coordinator_log, std::ios::app);
    append << "four\n";
  }
  const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(10));
  while (absl::Now() < deadline && ReadFile(followed).value_or("") != "four\n") {
    absl::SleepFor(absl::Milliseconds(50));
  }
  EXPECT_EQ(ReadFile(followed).value_or(""), "four\n");
  follow->Stop(absl::Seconds(2));
}

// `dcs up` starts the learner with the pinned numeric kernels (common/pinned_kernels.h), over
// a user's own choice: libtorch starts once in the cluster, and the learner registers with the
// pinned kernels, as `dcs status` shows.
TEST(DcsCliTest, UpStartsTheLearnerWithThePinnedKernels) {
  const std::string data_dir = MakeTempDir();
  ScopedVariable blas("OPENBLAS_CORETYPE", "Prescott");
  ScopedVariable threads("OPENBLAS_NUM_THREADS", "2");
  ScopedVariable aten("ATEN_CPU_CAPABILITY", "default");
  const LoaderReport loader;
  const RunResult up = Dcs({"up", "--detach", "--actors=1", "--data-dir", data_dir});
  const RunResult json = Dcs({"status", "-o", "json", "--data-dir", data_dir});
  const RunResult down = Dcs({"down", "--data-dir", data_dir});
  ASSERT_EQ(up.exit_code, 0) << up.output;
  EXPECT_EQ(down.exit_code, 0) << down.output;
  EXPECT_EQ(loader.LibtorchStarts(), 1);

  ASSERT_EQ(json.exit_code, 0) << json.output;
  google::protobuf::Struct parsed;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(json.output, &parsed).ok())
      << json.output;
  std::map<std::string, std::string> learner;
  for (const google::protobuf::Value& worker :
       parsed.fields().at("workers").list_value().values()) {
    const auto& info = worker.struct_value().fields().at("info").struct_value().fields();
    if (info.at("role").string_value() != "learner") continue;
    for (const google::protobuf::Value& library :
         info.at("build").struct_value().fields().at("libraries").list_value().values()) {
      const auto& fields = library.struct_value().fields();
      learner[fields.at("name").string_value()] = fields.at("version").string_value();
    }
  }
  EXPECT_EQ(learner["openblas core"], "Haswell");
  // scripts/bootstrap installs the pthread build, which locks its buffers (BlasMutex).
  EXPECT_EQ(learner["openblas build"], "pthread, 1 thread");
  EXPECT_EQ(learner["aten cpu capability"], "avx2");
}

TEST(DcsCliTest, CtrlCStopsTheForegroundClusterLeavingNothingBehind) {
  const std::string data_dir = MakeTempDir();
  std::optional<ForegroundUp> up = StartForegroundUp(data_dir);
  ASSERT_TRUE(up.has_value());
  ASSERT_THAT(up->state.processes, SizeIs(4));

  ::kill(up->dcs.pid(), SIGINT);
  std::optional<int> status = up->dcs.Wait(testing::Patient(absl::Seconds(30)));
  ASSERT_TRUE(status.has_value()) << "dcs up did not stop";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0)
      << services::cli::DescribeExit(*status) << "\n" << ReadFile(up->output_path).value_or("");
  ExpectAllStopped(up->state);
}

TEST(DcsCliTest, DownStopsAForegroundClusterThroughItsSupervisor) {
  const std::string data_dir = MakeTempDir();
  std::optional<ForegroundUp> up = StartForegroundUp(data_dir);
  ASSERT_TRUE(up.has_value());

  const RunResult down = Dcs({"down", "--data-dir", data_dir});
  EXPECT_EQ(down.exit_code, 0) << down.output;
  std::optional<int> status = up->dcs.Wait(testing::Patient(absl::Seconds(30)));
  ASSERT_TRUE(status.has_value()) << "dcs up did not stop";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0)
      << services::cli::DescribeExit(*status);
  ExpectAllStopped(up->state);
}

TEST(DcsCliTest, AProcessThatDiesStopsTheForegroundClusterWithAnError) {
  const std::string data_dir = MakeTempDir();
  std::optional<ForegroundUp> up = StartForegroundUp(data_dir);
  ASSERT_TRUE(up.has_value());
  const services::cli::ClusterProcess& learner = up->state.processes[1];
  ASSERT_EQ(learner.name, "learner");

  ::kill(learner.pid, SIGKILL);
  std::optional<int> status = up->dcs.Wait(testing::Patient(absl::Seconds(30)));
  ASSERT_TRUE(status.has_value()) << "dcs up did not notice";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == services::kExitFailure)
      << services::cli::DescribeExit(*status);
  EXPECT_THAT(ReadFile(up->output_path).value_or(""), HasSubstr("learner killed by SIGKILL"));
  ExpectAllStopped(up->state);
}

TEST(DcsCliTest, StatusOfAnUnreachableCoordinatorIsOneLineAndUnavailableExit) {
  const RunResult status =
      Dcs({"status", "--addr", absl::StrCat("127.0.0.1:", PickFreePort()), "--timeout=2s"});
  EXPECT_EQ(status.exit_code, services::kExitUnavailable);
  ASSERT_THAT(Lines(status.output), SizeIs(1)) << status.output;
  EXPECT_THAT(status.output, HasSubstr("UNAVAILABLE"));
}

TEST(DcsCliTest, DownWithoutAClusterSaysSo) {
  const RunResult down = Dcs({"down", "--data-dir", MakeTempDir()});
  EXPECT_EQ(down.exit_code, services::kExitFailure);
  ASSERT_THAT(Lines(down.output), SizeIs(1)) << down.output;
  EXPECT_THAT(down.output, HasSubstr("no local cluster"));
}

TEST(DcsCliTest, EveryCommandHasHelp) {
  for (const char* command : {"up", "down", "status", "health", "version", "train"}) {
    const RunResult help = Dcs({command, "--help"});
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_THAT(help.output, HasSubstr(absl::StrCat("dcs ", command))) << help.output;
  }
}

TEST(DcsCliTest, RolloutPrintsTheReturnStatisticsOfABaselinePolicy) {
  const RunResult rollout =
      Dcs({"env", "rollout", "--env", "cartpole", "--episodes", "20", "--seed", "3"});
  ASSERT_EQ(rollout.exit_code, 0) << rollout.output;
  // A random CartPole policy lasts about 22 steps (Gymnasium's figure); one row of statistics.
  const std::vector<std::string> lines = Lines(rollout.output);
  ASSERT_THAT(lines, SizeIs(2)) << rollout.output;
  std::vector<std::string> cells = absl::StrSplit(lines[1], ' ', absl::SkipEmpty());
  ASSERT_THAT(cells, SizeIs(7)) << lines[1];
  EXPECT_EQ(cells[0], "cartpole");
  EXPECT_EQ(cells[2], "20");
  const double mean = std::stod(cells[3]);
  EXPECT_GT(mean, 12);
  EXPECT_LT(mean, 40);
  // The same seed gives the same episodes.
  EXPECT_EQ(Dcs({"env", "rollout", "--env", "cartpole", "--episodes", "20", "--seed", "3"}).output,
            rollout.output);

  const RunResult unknown = Dcs({"env", "rollout", "--env", "cartpole", "--policy", "smart"});
  EXPECT_EQ(unknown.exit_code, services::kExitDataError);
  EXPECT_THAT(unknown.output, HasSubstr("no baseline policy 'smart'"));
}

TEST(DcsCliTest, RenderWritesOnePngFramePerStep) {
  const std::string dir = MakeTempDir();
  const RunResult render = Dcs({"env", "render", "--env", "cartpole", "--steps", "5", "--seed",
                                "1", "--set", "length=1.0", "--out", dir});
  ASSERT_EQ(render.exit_code, 0) << render.output;
  // Frames of the reset and of each step (a random episode lasts longer than 5 steps).
  for (int frame = 0; frame <= 5; ++frame) {
    const std::string path = absl::StrFormat("%s/frame_%05d.png", dir, frame);
    const std::string bytes = ReadFile(path).value_or("");
    ASSERT_GT(bytes.size(), 8u) << path;
    EXPECT_EQ(bytes.substr(1, 3), "PNG") << path;
  }
  EXPECT_FALSE(std::filesystem::exists(absl::StrFormat("%s/frame_%05d.png", dir, 6)));
  const RunResult bad = Dcs({"env", "render", "--env", "cartpole", "--set", "length=99",
                             "--out", dir});
  EXPECT_EQ(bad.exit_code, services::kExitDataError);
  EXPECT_THAT(bad.output, HasSubstr("length"));
}

TEST(DcsCliTest, VersionListsTheLinkedLibraries) {
  const RunResult version = Dcs({"version"});
  EXPECT_EQ(version.exit_code, 0);
  for (const char* library : {"grpc", "protobuf", "libtorch", "box2d", "sqlite", "eigen"}) {
    EXPECT_THAT(version.output, HasSubstr(library));
  }
}

// `dcs version` answers without libtorch (no start of it in the loader's report, dcs-train
// not run), yet names libtorch's version, as compiled against, and the kernels every trainer
// pins, from their one table.
TEST(DcsCliTest, VersionShowsLibtorchAndThePinnedKernelsWithoutLoadingLibtorch) {
  const LoaderReport loader;
  const RunResult version = Dcs({"version"});
  ASSERT_EQ(version.exit_code, 0) << version.output;
  EXPECT_EQ(loader.LibtorchStarts(), 0);
  EXPECT_THAT(version.output, ContainsRegex("\nlibtorch +[0-9]+\\.[0-9]+\\.[0-9]+\n"));
  EXPECT_THAT(version.output, HasSubstr("\nPINNED KERNEL SETTING  VALUE\n"));
  for (const KernelVariable& variable : kPinnedKernels) {
    EXPECT_THAT(version.output,
                ContainsRegex(absl::StrCat("\n", variable.name, " +", variable.value, "\n")));
  }
}

}  // namespace
}  // namespace dcs::integration
