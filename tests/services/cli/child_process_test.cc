// Copyright 2026 The DCS Authors.
#include "services/cli/child_process.h"

#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/eventually.h"

namespace dcs::services::cli {
namespace {

using ::testing::HasSubstr;

// Generous: only reached if something is broken.
constexpr absl::Duration kLongTimeout = absl::Seconds(10);

ChildProcess MustStart(const std::string& path, std::vector<std::string> args,
                       const std::string& output_path = "") {
  absl::StatusOr<ChildProcess> child =
      ChildProcess::Start({.path = path, .args = std::move(args), .output_path = output_path});
  EXPECT_TRUE(child.ok()) << child.status();
  if (!child.ok()) std::abort();
  return *std::move(child);
}

TEST(ChildProcessTest, TrueExitsWithStatusZero) {
  ChildProcess child = MustStart("/bin/true", {});
  EXPECT_GT(child.pid(), 0);
  const std::optional<int> status = child.Wait(kLongTimeout);
  ASSERT_TRUE(status.has_value());
  EXPECT_TRUE(WIFEXITED(*status));
  EXPECT_EQ(WEXITSTATUS(*status), 0);
  EXPECT_EQ(DescribeExit(*status), "exited with status 0");
  // Reaped: polling again returns the same status.
  EXPECT_EQ(child.Poll(), status);
  EXPECT_EQ(child.pid(), -1);
}

TEST(ChildProcessTest, ExitStatusIsReported) {
  ChildProcess child = MustStart("/bin/sh", {"-c", "exit 3"});
  const std::optional<int> status = child.Wait(kLongTimeout);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(WEXITSTATUS(*status), 3);
  EXPECT_EQ(DescribeExit(*status), "exited with status 3");
}

TEST(ChildProcessTest, ArgumentsArePassedVerbatim) {
  std::string pattern = ::testing::TempDir() + "child_process_test.XXXXXX";
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::string output = pattern + "/out.txt";
  ChildProcess child =
      MustStart("/bin/sh", {"-c", "printf '%s|' \"$@\"", "sh", "a b", "", "c"}, output);
  ASSERT_TRUE(child.Wait(kLongTimeout).has_value());
  EXPECT_EQ(dcs::ReadFile(output).value_or("<error>"), "a b||c|");
  std::filesystem::remove_all(pattern);
}

// The child's environment is exactly the one given (`dcs up` starts the learner with the
// pinned numeric kernels so), and ours without one.
TEST(ChildProcessTest, EnvironmentIsTheGivenOneElseOurs) {
  std::string pattern = ::testing::TempDir() + "child_process_test.XXXXXX";
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  ASSERT_EQ(::setenv("DCS_CHILD_PROCESS_TEST", "ours", /*overwrite=*/1), 0);
  const std::string given = pattern + "/given.txt";
  absl::StatusOr<ChildProcess> child =
      ChildProcess::Start({.path = "/usr/bin/env",
                           .output_path = given,
                           .environment = std::vector<std::string>{"A=1", "B=two words"}});
  ASSERT_TRUE(child.ok()) << child.status();
  ASSERT_TRUE(child->Wait(kLongTimeout).has_value());
  EXPECT_EQ(dcs::ReadFile(given).value_or("<error>"), "A=1\nB=two words\n");

  const std::string inherited = pattern + "/inherited.txt";
  ChildProcess own = MustStart("/bin/sh", {"-c", "printf %s \"$DCS_CHILD_PROCESS_TEST\""},
                               inherited);
  ASSERT_TRUE(own.Wait(kLongTimeout).has_value());
  EXPECT_EQ(dcs::ReadFile(inherited).value_or("<error>"), "ours");
  ::unsetenv("DCS_CHILD_PROCESS_TEST");
  std::filesystem::remove_all(pattern);
}

TEST(ChildProcessTest, MissingExecutableIsNotFoundNamingThePath) {
  const std::string path = "/nonexistent/dcs-no-such-program";
  const absl::StatusOr<ChildProcess> child = ChildProcess::Start({.path = path});
  EXPECT_EQ(child.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(child.status().message(), HasSubstr(path));
}

TEST(ChildProcessTest, NonExecutableFileIsPermissionDenied) {
  // A directory cannot be executed (EACCES), even by root.
  const absl::StatusOr<ChildProcess> child = ChildProcess::Start({.path = "/tmp"});
  EXPECT_EQ(child.status().code(), absl::StatusCode::kPermissionDenied);
  EXPECT_THAT(child.status().message(), HasSubstr("/tmp"));
}

TEST(ChildProcessTest, StopTerminatesWithSigterm) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  const int status = child.Stop(kLongTimeout);
  ASSERT_TRUE(WIFSIGNALED(status)) << DescribeExit(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(DescribeExit(status), "killed by SIGTERM");
  EXPECT_EQ(child.pid(), -1);
}

TEST(ChildProcessTest, StopKillsAChildThatIgnoresSigterm) {
  // `exec` so that the process that ignores SIGTERM is the child itself, not a grandchild.
  ChildProcess child = MustStart("/bin/sh", {"-c", "trap '' TERM; exec sleep 30"});
  const pid_t pid = child.pid();
  // Let the shell install the trap before stopping; otherwise SIGTERM would simply kill it.
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  const int status = child.Stop(absl::Milliseconds(200));
  ASSERT_TRUE(WIFSIGNALED(status)) << DescribeExit(status);
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
  EXPECT_EQ(DescribeExit(status), "killed by SIGKILL");
}

TEST(ChildProcessTest, StopWithoutGraceKills) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  const int status = child.Stop(absl::ZeroDuration());
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGKILL);
}

TEST(ChildProcessTest, StopAfterExitReturnsTheExitStatus) {
  ChildProcess child = MustStart("/bin/sh", {"-c", "exit 7"});
  ASSERT_TRUE(child.Wait(kLongTimeout).has_value());
  const int status = child.Stop(kLongTimeout);
  EXPECT_EQ(DescribeExit(status), "exited with status 7");
}

TEST(ChildProcessTest, OutputPathCapturesStdoutAndStderr) {
  std::string pattern = ::testing::TempDir() + "child_process_test.XXXXXX";
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::string output = pattern + "/child.log";
  {
    ChildProcess child = MustStart("/bin/sh", {"-c", "echo to-stdout; echo to-stderr >&2"}, output);
    ASSERT_TRUE(child.Wait(kLongTimeout).has_value());
  }
  {
    // Appends rather than truncates.
    ChildProcess child = MustStart("/bin/sh", {"-c", "echo again"}, output);
    ASSERT_TRUE(child.Wait(kLongTimeout).has_value());
  }
  EXPECT_EQ(dcs::ReadFile(output).value_or("<error>"), "to-stdout\nto-stderr\nagain\n");
  std::filesystem::remove_all(pattern);
}

TEST(ChildProcessTest, UnopenableOutputPathIsAnError) {
  const absl::StatusOr<ChildProcess> child =
      ChildProcess::Start({.path = "/bin/true", .output_path = "/nonexistent/dir/out.log"});
  EXPECT_FALSE(child.ok());
  EXPECT_THAT(child.status().message(), HasSubstr("/nonexistent/dir/out.log"));
}

TEST(ChildProcessTest, RunsInTheWorkingDirectory) {
  std::string pattern = ::testing::TempDir() + "child_process_test.XXXXXX";
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::string dir = std::filesystem::canonical(pattern).string();
  const std::string output = dir + "/pwd.log";
  {
    absl::StatusOr<ChildProcess> child = ChildProcess::Start({.path = "/bin/sh",
                                                              .args = {"-c", "pwd"},
                                                              .output_path = output,
                                                              .working_directory = dir});
    ASSERT_TRUE(child.ok()) << child.status();
    ASSERT_TRUE(child->Wait(kLongTimeout).has_value());
  }
  EXPECT_EQ(dcs::ReadFile(output).value_or("<error>"), dir + "\n");
  std::filesystem::remove_all(dir);
}

TEST(ChildProcessTest, MissingWorkingDirectoryIsNotFoundNamingIt) {
  const absl::StatusOr<ChildProcess> child =
      ChildProcess::Start({.path = "/bin/true", .working_directory = "/nonexistent/dir"});
  EXPECT_EQ(child.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(child.status().message(), HasSubstr("/nonexistent/dir"));
}

TEST(ChildProcessTest, WaitTimesOutForARunningChild) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  EXPECT_EQ(child.Wait(absl::Milliseconds(50)), std::nullopt);
  EXPECT_EQ(child.Poll(), std::nullopt);
  EXPECT_GT(child.pid(), 0);
  child.Stop(absl::ZeroDuration());
}

TEST(ChildProcessTest, ChildRunsInItsOwnProcessGroup) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  // setpgid runs in the child after fork; wait until it has.
  EXPECT_TRUE(
      testing::Eventually([&] { return ::getpgid(child.pid()) == child.pid(); }, kLongTimeout));
  EXPECT_NE(::getpgid(child.pid()), ::getpgrp());
  child.Stop(absl::ZeroDuration());
}

TEST(ChildProcessTest, DestructorKillsAndReapsTheChild) {
  pid_t pid = -1;
  {
    ChildProcess child = MustStart("/bin/sleep", {"30"});
    pid = child.pid();
    ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  }
  // Reaped, not a zombie: the pid no longer exists as our child.
  EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), -1);
  EXPECT_FALSE(IsProcessRunning(pid, "sleep"));
}

TEST(ChildProcessTest, MoveTransfersOwnership) {
  ChildProcess first = MustStart("/bin/sleep", {"30"});
  const pid_t pid = first.pid();
  ChildProcess second = std::move(first);
  EXPECT_EQ(second.pid(), pid);
  EXPECT_EQ(first.pid(), -1);  // NOLINT(bugprone-use-after-move): documents the moved-from state
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  const int status = second.Stop(kLongTimeout);
  EXPECT_TRUE(WIFSIGNALED(status));
}

TEST(IsProcessRunningTest, MatchesRunningChildByExecutableName) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  const pid_t pid = child.pid();
  // Right after fork the child is still this test binary; it becomes `sleep` at exec.
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  EXPECT_FALSE(IsProcessRunning(pid, "dcs-coordinator"));
  child.Stop(kLongTimeout);
  EXPECT_FALSE(IsProcessRunning(pid, "sleep"));
}

TEST(IsProcessRunningTest, ExitedButUnreapedChildCountsAsGone) {
  ChildProcess child = MustStart("/bin/sleep", {"1"});
  const pid_t pid = child.pid();
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  // Without Poll() the child stays a zombie after it exits; it must not count as running.
  EXPECT_TRUE(testing::Eventually([&] { return !IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  EXPECT_EQ(::kill(pid, 0), 0) << "the zombie should still exist until reaped";
  EXPECT_TRUE(child.Wait(kLongTimeout).has_value());
}

TEST(IsProcessRunningTest, InvalidPidsAreNotRunning) {
  EXPECT_FALSE(IsProcessRunning(0, "sleep"));
  EXPECT_FALSE(IsProcessRunning(-1, "sleep"));
}

TEST(ChildProcessTest, ReleaseLeavesTheProcessRunning) {
  pid_t pid = -1;
  {
    ChildProcess child = MustStart("/bin/sleep", {"30"});
    pid = child.pid();
    EXPECT_EQ(child.Release(), pid);
    EXPECT_EQ(child.pid(), -1);
  }
  EXPECT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  // Still our child: kill and reap it here.
  ASSERT_EQ(::kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status));
}

TEST(StopProcessTest, StopsAProcessThatIsNotOwned) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  const pid_t pid = child.pid();
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  // StopProcess cannot reap (the process is ours, but StopProcess does not know it); a zombie
  // counts as exited, so it returns true once SIGTERM took effect.
  EXPECT_TRUE(StopProcess(pid, "sleep", kLongTimeout));
  const std::optional<int> status = child.Wait(kLongTimeout);
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(DescribeExit(*status), "killed by SIGTERM");
}

TEST(StopProcessTest, ProcessWithAnotherNameIsLeftAlone) {
  ChildProcess child = MustStart("/bin/sleep", {"30"});
  const pid_t pid = child.pid();
  ASSERT_TRUE(testing::Eventually([&] { return IsProcessRunning(pid, "sleep"); }, kLongTimeout));
  EXPECT_TRUE(StopProcess(pid, "dcs-actor", kLongTimeout));
  EXPECT_EQ(child.Poll(), std::nullopt);
  EXPECT_TRUE(IsProcessRunning(pid, "sleep"));
  child.Stop(absl::ZeroDuration());
}

TEST(DescribeExitTest, DescribesExitAndSignals) {
  EXPECT_EQ(DescribeExit(0), "exited with status 0");
  EXPECT_EQ(DescribeExit(2 << 8), "exited with status 2");
  EXPECT_EQ(DescribeExit(SIGKILL), "killed by SIGKILL");
  EXPECT_EQ(DescribeExit(SIGSEGV), "killed by SIGSEGV");
}

}  // namespace
}  // namespace dcs::services::cli
