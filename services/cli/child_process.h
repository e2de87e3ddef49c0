// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_CHILD_PROCESS_H_
#define DCS_SERVICES_CLI_CHILD_PROCESS_H_

// Child processes, for `dcs up` and for tests that start real DCS processes. A ChildProcess
// owns a running child: destroying it kills (SIGKILL) and reaps the child unless Release()d.
// The child starts with no signal blocked, in a process group of its own (so a terminal's
// Ctrl-C reaches only the parent, which stops its children in order), and by default receives
// SIGTERM if the parent dies, so no child outlives a crashed `dcs up`. With `pipe_input` its
// stdin is a stream this process writes (WriteInput), e.g. video frames for ffmpeg.
// Thread-compatible.

#include <sys/types.h>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"

namespace dcs::services::cli {

struct ChildProcessOptions {
  std::string path;               // the executable
  std::vector<std::string> args;  // without argv[0]
  std::string output_path;        // stdout and stderr are appended here; empty: inherited
  std::string working_directory;  // the child's (a relative `path` starts there); empty: ours
  // The child's whole environment, "NAME=value" each; nullopt: ours.
  std::optional<std::vector<std::string>> environment;
  bool new_session = false;       // setsid(): detached from the terminal, outlives the parent
  bool stop_with_parent = true;   // SIGTERM when the parent dies (ignored with new_session)
  bool pipe_input = false;        // stdin: a stream from WriteInput; false: inherited
};

class ChildProcess {
 public:
  // NOT_FOUND or PERMISSION_DENIED (naming the path) if the executable cannot be run or the
  // working directory cannot be entered; the error of opening `output_path`.
  static absl::StatusOr<ChildProcess> Start(const ChildProcessOptions& options);

  ChildProcess(ChildProcess&& other) noexcept;
  ChildProcess& operator=(ChildProcess&& other) noexcept;
  ~ChildProcess();

  pid_t pid() const { return pid_; }

  // Writes all of `bytes` to the child's stdin (started with pipe_input), blocking while the
  // child does not read. UNAVAILABLE if the child has closed its stdin or exited;
  // FAILED_PRECONDITION if the input is closed or was never piped.
  absl::Status WriteInput(std::span<const uint8_t> bytes);

  // Closes the child's stdin (it reads end of file). Idempotent.
  void CloseInput();

  // The child's wait status if it has exited (it is then reaped), without blocking.
  std::optional<int> Poll();

  // Waits up to `timeout` for the child to exit; its wait status, or nullopt if still running.
  std::optional<int> Wait(absl::Duration timeout);

  // SIGTERM, up to `grace` to exit, then SIGKILL. Returns the wait status (0 if this object
  // no longer owns a process).
  int Stop(absl::Duration grace);

  // Gives up ownership: the child keeps running after this object is gone.
  pid_t Release();

 private:
  ChildProcess(pid_t pid, int input_fd) : pid_(pid), input_fd_(input_fd) {}

  pid_t pid_ = -1;                  // -1 once reaped or released
  int input_fd_ = -1;               // our end of the child's stdin; -1 if none or closed
  std::optional<int> exit_status_;  // set once reaped
};

// `program` (made absolute) if it names a path, else the first executable file of that name on
// PATH (/usr/bin:/bin if PATH is unset); nullopt if there is none.
std::optional<std::string> FindProgram(const std::string& program);

// "exited with status 0", "killed by SIGKILL".
std::string DescribeExit(int wait_status);

// Whether `pid` names a running process (a zombie counts as gone) whose executable is named
// `executable_name` (a pid reused by another program counts as gone too).
bool IsProcessRunning(pid_t pid, const std::string& executable_name);

// Stops a process that is not our child: SIGTERM, up to `grace` to exit, then SIGKILL.
// Returns true if it exited within `grace`.
bool StopProcess(pid_t pid, const std::string& executable_name, absl::Duration grace);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_CHILD_PROCESS_H_
