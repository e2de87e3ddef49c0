// Copyright 2026 The DCS Authors.
//
// Bad input gets one clear error line and a documented non-zero exit, never a stack dump:
// unknown flags, unreadable or malformed config files, ports in use; and a worker whose
// coordinator is unreachable retries with backoff, says so, and registers once it can.

#include <signal.h>
#include <sys/wait.h>

#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "services/cli/cluster_client.h"
#include "services/exit_codes.h"
#include "services/port_file.h"
#include "tests/integration/test_util.h"
#include "tests/testing/eventually.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using dcs::testing::Eventually;
using dcs::testing::MakeTempDir;
using dcs::testing::PickFreePort;
using ::testing::HasSubstr;
using ::testing::SizeIs;

// A dcs-coordinator on ephemeral ports, and the ports it got.
struct RunningCoordinator {
  services::cli::ChildProcess process;
  services::BoundPorts ports;
};

RunningCoordinator StartCoordinator(const std::string& listen = "127.0.0.1:0") {
  const std::string dir = MakeTempDir();
  const std::string port_file = absl::StrCat(dir, "/ports");
  absl::StatusOr<services::cli::ChildProcess> process = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs-coordinator"),
       .args = {absl::StrCat("--listen=", listen), "--metrics-listen=127.0.0.1:0",
                absl::StrCat("--port-file=", port_file)},
       .output_path = absl::StrCat(dir, "/log")});
  EXPECT_TRUE(process.ok()) << process.status();
  std::optional<services::BoundPorts> ports;
  EXPECT_TRUE(Eventually([&] { return (ports = services::ReadPortFile(port_file)).has_value(); }));
  return {*std::move(process), ports.value_or(services::BoundPorts{})};
}

TEST(BadInputTest, TheExampleConfigIsValid) {
  const std::string dir = MakeTempDir();
  const std::string port_file = absl::StrCat(dir, "/ports");
  // The example's fixed ports may be taken on this machine: the command line wins over them.
  absl::StatusOr<services::cli::ChildProcess> coordinator = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs-coordinator"),
       .args = {"--config", DCS_SOURCE_DIR "/configs/coordinator.yaml", "--listen=127.0.0.1:0",
                "--metrics-listen=127.0.0.1:0", absl::StrCat("--port-file=", port_file)},
       .output_path = absl::StrCat(dir, "/log")});
  ASSERT_TRUE(coordinator.ok()) << coordinator.status();
  EXPECT_TRUE(Eventually([&] { return services::ReadPortFile(port_file).has_value(); }));
  EXPECT_FALSE(coordinator->Poll().has_value()) << "exited";
}

TEST(BadInputTest, UnknownFlagIsOneLineAndUsageExit) {
  for (const char* program : {"dcs-coordinator", "dcs-learner", "dcs-actor", "dcs"}) {
    SCOPED_TRACE(program);
    const RunResult result = RunProgram(BinaryPath(program), {"--no-such-flag"});
    EXPECT_EQ(result.exit_code, services::kExitUsage);
    ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
    EXPECT_THAT(result.output, HasSubstr("--no-such-flag"));
  }
}

TEST(BadInputTest, BadFlagValueIsOneLineAndUsageExit) {
  const RunResult result = RunProgram(BinaryPath("dcs-coordinator"), {"--worker-timeout=soon"});
  EXPECT_EQ(result.exit_code, services::kExitUsage);
  ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--worker-timeout"));
}

TEST(BadInputTest, UnreadableConfigFileIsOneLineAndConfigExit) {
  const RunResult result =
      RunProgram(BinaryPath("dcs-learner"), {"--config", "/nonexistent/learner.yaml"});
  EXPECT_EQ(result.exit_code, services::kExitConfig);
  ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
  EXPECT_THAT(result.output, HasSubstr("/nonexistent/learner.yaml"));
}

TEST(BadInputTest, MalformedConfigFileNamesTheLine) {
  const std::string path = absl::StrCat(MakeTempDir(), "/actor.yaml");
  ASSERT_TRUE(WriteFileAtomically(path, "coordinator: 127.0.0.1:1\nlisten: [unclosed\n").ok());
  const RunResult result = RunProgram(BinaryPath("dcs-actor"), {"--config", path});
  EXPECT_EQ(result.exit_code, services::kExitConfig);
  ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
  EXPECT_THAT(result.output, HasSubstr("line 3"));
}

TEST(BadInputTest, UnknownConfigKeyIsNamed) {
  const std::string path = absl::StrCat(MakeTempDir(), "/coordinator.yaml");
  ASSERT_TRUE(WriteFileAtomically(path, "worker_timeout: 10s\nlissten: 127.0.0.1:0\n").ok());
  const RunResult result = RunProgram(BinaryPath("dcs-coordinator"), {"--config", path});
  EXPECT_EQ(result.exit_code, services::kExitConfig);
  ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
  EXPECT_THAT(result.output, HasSubstr("'lissten'"));
}

TEST(BadInputTest, InconsistentSettingsAreOneLineAndDataErrorExit) {
  const RunResult result =
      RunProgram(BinaryPath("dcs-coordinator"), {"--heartbeat-interval=2s", "--worker-timeout=3s",
                                          "--metrics-listen=127.0.0.1:0", "--listen=127.0.0.1:0"});
  EXPECT_EQ(result.exit_code, services::kExitDataError);
  ASSERT_THAT(Lines(result.output), SizeIs(1)) << result.output;
  EXPECT_THAT(result.output, HasSubstr("twice the heartbeat interval"));
}

TEST(BadInputTest, PortInUseIsOneLineAndUnavailableExit) {
  RunningCoordinator first = StartCoordinator();
  ASSERT_NE(first.ports.grpc, 0);
  const RunResult grpc_taken =
      RunProgram(BinaryPath("dcs-coordinator"), {absl::StrCat("--listen=127.0.0.1:", first.ports.grpc),
                                          "--metrics-listen=127.0.0.1:0"});
  EXPECT_EQ(grpc_taken.exit_code, services::kExitUnavailable);
  ASSERT_THAT(Lines(grpc_taken.output), SizeIs(1)) << grpc_taken.output;
  EXPECT_THAT(grpc_taken.output,
              HasSubstr(absl::StrCat("127.0.0.1:", first.ports.grpc, ": Address already in use")));

  const RunResult metrics_taken = RunProgram(
      BinaryPath("dcs-coordinator"),
      {"--listen=127.0.0.1:0", absl::StrCat("--metrics-listen=127.0.0.1:", first.ports.metrics)});
  EXPECT_EQ(metrics_taken.exit_code, services::kExitUnavailable);
  ASSERT_THAT(Lines(metrics_taken.output), SizeIs(1)) << metrics_taken.output;
  EXPECT_THAT(metrics_taken.output, HasSubstr("Address already in use"));
}

TEST(BadInputTest, WorkerRetriesAnUnreachableCoordinatorAndRegistersOnceItIsUp) {
  const int coordinator_port = PickFreePort();
  const std::string dir = MakeTempDir();
  const std::string log = absl::StrCat(dir, "/actor.log");
  const std::string port_file = absl::StrCat(dir, "/ports");
  absl::StatusOr<services::cli::ChildProcess> actor = services::cli::ChildProcess::Start(
      {.path = BinaryPath("dcs-actor"),
       .args = {absl::StrCat("--coordinator=127.0.0.1:", coordinator_port),
                absl::StrCat("--port-file=", port_file)},
       .output_path = log});
  ASSERT_TRUE(actor.ok()) << actor.status();

  // It says so, with the attempt number and the backoff before the next one.
  ASSERT_TRUE(Eventually([&] { return absl::StrContains(ReadFile(log).value_or(""), "attempt=3"); }))
      << ReadFile(log).value_or("");
  const std::string retrying = ReadFile(log).value_or("");
  EXPECT_THAT(retrying, HasSubstr("coordinator unreachable; retrying registration with backoff"));
  EXPECT_THAT(retrying, HasSubstr("retry_in="));
  // Not registered, so not ready for work.
  std::optional<services::BoundPorts> ports = services::ReadPortFile(port_file);
  ASSERT_TRUE(ports.has_value());
  const std::string actor_address = absl::StrCat("127.0.0.1:", ports->grpc);
  absl::StatusOr<bool> serving = services::cli::IsServing(actor_address, "", absl::Seconds(2));
  ASSERT_TRUE(serving.ok()) << serving.status();
  EXPECT_FALSE(*serving);

  RunningCoordinator coordinator = StartCoordinator(absl::StrCat("127.0.0.1:", coordinator_port));
  EXPECT_TRUE(Eventually([&] {
    absl::StatusOr<bool> now_serving =
        services::cli::IsServing(actor_address, "", absl::Seconds(1));
    return now_serving.ok() && *now_serving;
  })) << ReadFile(log).value_or("");
  EXPECT_THAT(ReadFile(log).value_or(""), HasSubstr("registered with the coordinator"));

  ::kill(actor->pid(), SIGTERM);
  std::optional<int> status = actor->Wait(absl::Seconds(5));
  ASSERT_TRUE(status.has_value()) << "dcs-actor did not stop within 5 s";
  EXPECT_TRUE(WIFEXITED(*status) && WEXITSTATUS(*status) == 0)
      << services::cli::DescribeExit(*status);
}

}  // namespace
}  // namespace dcs::integration
