// Copyright 2026 The DCS Authors.
#include "services/cli/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/time/clock.h"
#include "common/exec_array.h"

namespace dcs::services::cli {
namespace {

constexpr absl::Duration kPollInterval = absl::Milliseconds(20);

// What failed in the child before or at exec, with its errno, as the child reports it.
struct ExecError {
  int in_chdir = 0;  // 1: entering the working directory, 0: execve
  int error = 0;
};

// Runs in the forked child: only async-signal-safe calls until execve. On failure, writes an
// ExecError to `error_fd` (close-on-exec, so a successful exec closes it with nothing written).
[[noreturn]] void ExecChild(const ChildProcessOptions& options, char* const* argv,
                            char* const* envp, int input_fd, int output_fd, int error_fd,
                            pid_t parent) {
  sigset_t none;
  sigemptyset(&none);
  pthread_sigmask(SIG_SETMASK, &none, nullptr);
  if (options.new_session) {
    setsid();
  } else {
    setpgid(0, 0);
    if (options.stop_with_parent) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(127);  // the parent died before prctl took effect
    }
  }
  if (input_fd >= 0) dup2(input_fd, STDIN_FILENO);
  if (output_fd >= 0) {
    dup2(output_fd, STDOUT_FILENO);
    dup2(output_fd, STDERR_FILENO);
  }
  ExecError failure;
  if (!options.working_directory.empty() && chdir(options.working_directory.c_str()) != 0) {
    failure = {.in_chdir = 1, .error = errno};
  } else {
    execve(options.path.c_str(), argv, envp);
    failure = {.in_chdir = 0, .error = errno};
  }
  [[maybe_unused]] ssize_t written = write(error_fd, &failure, sizeof(failure));
  _exit(127);
}

}  // namespace

absl::StatusOr<ChildProcess> ChildProcess::Start(const ChildProcessOptions& options) {
  std::vector<std::string> arguments = {options.path};
  arguments.insert(arguments.end(), options.args.begin(), options.args.end());
  const std::vector<char*> argv = ExecArray(arguments);
  // Built before fork, as argv: the child may make async-signal-safe calls only.
  std::vector<std::string> environment = options.environment.value_or(std::vector<std::string>());
  const std::vector<char*> own_envp = ExecArray(environment);
  char* const* const envp = options.environment.has_value() ? own_envp.data() : environ;

  int output_fd = -1;
  if (!options.output_path.empty()) {
    output_fd = ::open(options.output_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC,
                       0644);
    if (output_fd < 0) {
      return absl::PermissionDeniedError(
          absl::StrCat("cannot open ", options.output_path, ": ", std::strerror(errno)));
    }
  }
  // A socket rather than a pipe for stdin: send() with MSG_NOSIGNAL reports a child that
  // stopped reading as EPIPE without raising SIGPIPE in this process.
  int input[2] = {-1, -1};
  if (options.pipe_input &&
      ::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, input) != 0) {
    if (output_fd >= 0) ::close(output_fd);
    return absl::InternalError(absl::StrCat("socketpair: ", std::strerror(errno)));
  }
  const auto close_input = [&input] {
    for (int fd : input) {
      if (fd >= 0) ::close(fd);
    }
  };
  int error_pipe[2];
  if (::pipe2(error_pipe, O_CLOEXEC) != 0) {
    if (output_fd >= 0) ::close(output_fd);
    close_input();
    return absl::InternalError(absl::StrCat("pipe: ", std::strerror(errno)));
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ExecChild(options, argv.data(), envp, input[0], output_fd, error_pipe[1], parent);
  }
  const int fork_errno = errno;
  ::close(error_pipe[1]);
  if (output_fd >= 0) ::close(output_fd);
  if (input[0] >= 0) ::close(std::exchange(input[0], -1));
  if (pid < 0) {
    close_input();
    ::close(error_pipe[0]);
    return absl::ResourceExhaustedError(absl::StrCat("fork: ", std::strerror(fork_errno)));
  }

  ExecError failure;
  ssize_t got;
  do {
    got = ::read(error_pipe[0], &failure, sizeof(failure));
  } while (got < 0 && errno == EINTR);
  ::close(error_pipe[0]);
  if (got == sizeof(failure)) {
    close_input();
    ::waitpid(pid, nullptr, 0);
    const std::string message =
        failure.in_chdir != 0
            ? absl::StrCat("cannot run ", options.path, " in ", options.working_directory, ": ",
                           std::strerror(failure.error))
            : absl::StrCat("cannot run ", options.path, ": ", std::strerror(failure.error));
    return failure.error == ENOENT ? absl::NotFoundError(message)
                                   : absl::PermissionDeniedError(message);
  }
  return ChildProcess(pid, input[1]);
}

ChildProcess::ChildProcess(ChildProcess&& other) noexcept
    : pid_(std::exchange(other.pid_, -1)),
      input_fd_(std::exchange(other.input_fd_, -1)),
      exit_status_(other.exit_status_) {}

ChildProcess& ChildProcess::operator=(ChildProcess&& other) noexcept {
  if (this != &other) {
    CloseInput();
    if (pid_ > 0) Stop(absl::ZeroDuration());
    pid_ = std::exchange(other.pid_, -1);
    input_fd_ = std::exchange(other.input_fd_, -1);
    exit_status_ = other.exit_status_;
  }
  return *this;
}

ChildProcess::~ChildProcess() {
  CloseInput();
  if (pid_ > 0) Stop(absl::ZeroDuration());
}

absl::Status ChildProcess::WriteInput(std::span<const uint8_t> bytes) {
  if (input_fd_ < 0) return absl::FailedPreconditionError("the child's input is not open");
  while (!bytes.empty()) {
    const ssize_t sent = ::send(input_fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent < 0) {
      return absl::UnavailableError(
          absl::StrCat("writing to process ", pid_, ": ", std::strerror(errno)));
    }
    bytes = bytes.subspan(static_cast<size_t>(sent));
  }
  return absl::OkStatus();
}

void ChildProcess::CloseInput() {
  if (input_fd_ >= 0) ::close(std::exchange(input_fd_, -1));
}

std::optional<int> ChildProcess::Poll() {
  if (pid_ <= 0) return exit_status_;
  int status = 0;
  const pid_t result = ::waitpid(pid_, &status, WNOHANG);
  if (result == pid_) {
    pid_ = -1;
    exit_status_ = status;
  }
  return exit_status_;
}

std::optional<int> ChildProcess::Wait(absl::Duration timeout) {
  const absl::Time deadline = absl::Now() + timeout;
  while (true) {
    if (std::optional<int> status = Poll()) return status;
    if (absl::Now() >= deadline) return std::nullopt;
    absl::SleepFor(kPollInterval);
  }
}

int ChildProcess::Stop(absl::Duration grace) {
  if (std::optional<int> status = Poll()) return *status;
  // Released or moved from: kill(-1, ...) would signal every process we may signal.
  if (pid_ <= 0) return 0;
  if (grace > absl::ZeroDuration()) {
    ::kill(pid_, SIGTERM);
    if (std::optional<int> status = Wait(grace)) return *status;
  }
  ::kill(pid_, SIGKILL);
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  exit_status_ = status;
  return status;
}

pid_t ChildProcess::Release() { return std::exchange(pid_, -1); }

std::optional<std::string> FindProgram(const std::string& program) {
  namespace fs = std::filesystem;
  const auto is_executable_file = [](const fs::path& path) {
    std::error_code error;
    return fs::is_regular_file(path, error) && ::access(path.c_str(), X_OK) == 0;
  };
  if (program.find('/') != std::string::npos) {
    if (!is_executable_file(program)) return std::nullopt;
    std::error_code error;
    const fs::path absolute = fs::absolute(program, error);
    return error ? program : absolute.string();
  }
  const char* path = std::getenv("PATH");
  for (absl::string_view dir : absl::StrSplit(path != nullptr ? path : "/usr/bin:/bin", ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : std::string(dir)) / program;
    std::error_code error;
    if (is_executable_file(candidate)) return fs::absolute(candidate, error).string();
  }
  return std::nullopt;
}

std::string DescribeExit(int wait_status) {
  if (WIFEXITED(wait_status)) return absl::StrCat("exited with status ", WEXITSTATUS(wait_status));
  if (WIFSIGNALED(wait_status)) {
    return absl::StrCat("killed by SIG", sigabbrev_np(WTERMSIG(wait_status)));
  }
  return absl::StrCat("wait status ", wait_status);
}

bool IsProcessRunning(pid_t pid, const std::string& executable_name) {
  if (pid <= 0 || ::kill(pid, 0) != 0) return false;
  std::ifstream stat(absl::StrCat("/proc/", pid, "/stat"));
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const size_t end_of_comm = text.rfind(')');
  if (end_of_comm == std::string::npos || end_of_comm + 2 >= text.size()) return false;
  if (text[end_of_comm + 2] == 'Z') return false;
  std::error_code error;
  const std::filesystem::path exe =
      std::filesystem::read_symlink(absl::StrCat("/proc/", pid, "/exe"), error);
  // Another user's process hides its exe: trust the pid then. A rebuilt binary reads
  // "dcs-actor (deleted)".
  const std::string name = exe.filename().string();
  return error || name == executable_name || name == executable_name + " (deleted)";
}

bool StopProcess(pid_t pid, const std::string& executable_name, absl::Duration grace) {
  if (!IsProcessRunning(pid, executable_name)) return true;
  ::kill(pid, SIGTERM);
  const absl::Time deadline = absl::Now() + grace;
  while (absl::Now() < deadline) {
    if (!IsProcessRunning(pid, executable_name)) return true;
    absl::SleepFor(kPollInterval);
  }
  ::kill(pid, SIGKILL);
  return false;
}

}  // namespace dcs::services::cli
