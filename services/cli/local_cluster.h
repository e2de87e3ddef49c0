// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_LOCAL_CLUSTER_H_
#define DCS_SERVICES_CLI_LOCAL_CLUSTER_H_

// A DCS cluster on this machine, as child processes on loopback: `dcs up` and `dcs down`.
//
// Layout of the data directory (./dcs-data by default: FindDataDir):
//   cluster.yaml         the running cluster: supervisor pid, every process's pid and addresses
//                        (how `dcs status` and `dcs down` find it)
//   prometheus-targets.yml  every process's /metrics address, a Prometheus file_sd file
//                        (deploy/prometheus/local.yml scrapes ./dcs-data's)
//   token                the cluster's bearer token, when it has one (mode 0600; the `dcs`
//                        client reads it to call this cluster's coordinator)
//   logs/<name>.log      each process's stdout and stderr
//   run/<name>.ports     each process's bound ports (--port-file)
//
// Start-up order is coordinator, learner, actors; the cluster is up once every worker is
// SERVING, which a worker is only while registered with the coordinator. Shutdown runs in the
// reverse order, so workers leave the coordinator cleanly. Confined to one thread.

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "services/auth.h"
#include "services/cli/child_process.h"

namespace dcs::services::cli {

struct LocalClusterOptions {
  std::string data_dir;  // laid out as above
  std::string bin_dir;   // holds dcs-coordinator, dcs-learner, dcs-actor
  int actors = 2;
  std::string coordinator_listen = "127.0.0.1:0";
  bool detach = false;  // children in their own sessions, left running when `dcs up` exits
  // The cluster's bearer token (services/auth.h), written to <data_dir>/token (mode 0600) and
  // required by every process; empty: none.
  std::string token;
  TlsFiles tls;  // mutual TLS between every process and its clients (services/auth.h); or none
  absl::Duration start_timeout = absl::Seconds(30);
  // Polled while starting: true aborts the start-up (Ctrl-C), which then returns CANCELLED.
  std::function<bool()> interrupted = [] { return false; };
};

// One process of a local cluster, as recorded in cluster.yaml.
struct ClusterProcess {
  std::string name;        // "coordinator", "learner", "actor-1", ...
  std::string executable;  // "dcs-actor"
  pid_t pid = 0;
  std::string grpc_address;
  std::string metrics_address;
};

struct ClusterState {
  pid_t supervisor_pid = 0;  // the `dcs up` in the foreground; 0 when detached
  std::string coordinator_address;
  std::vector<ClusterProcess> processes;  // in start-up order
};

// Where a cluster in `data_dir` keeps its token.
std::string TokenPath(const std::string& data_dir);

// Where a cluster in `data_dir` keeps the log of its process `name` (`dcs logs`).
std::string ProcessLogPath(const std::string& data_dir, const std::string& name);

// The data directory `dcs` uses when none is named (--data-dir, DCS_DATA_DIR), seen from the
// directory `from`: the nearest `dcs-data` of `from` or one of its parents that records a
// cluster (`dcs up` started one there, and no `dcs down` has stopped it), so that a command
// finds the local cluster from any directory of the project; "dcs-data" (in `from`) if none
// does.
std::string FindDataDir(const std::filesystem::path& from);

// The cluster recorded in `data_dir`. FAILED_PRECONDITION if none is (no cluster was started
// there: a state, not a missing input); DATA_LOSS if cluster.yaml is unreadable.
absl::StatusOr<ClusterState> ReadClusterState(const std::string& data_dir);

// Whether any process of `state` still runs.
bool IsAnyRunning(const ClusterState& state);

class LocalCluster {
 public:
  // Starts every process and waits until all are SERVING. FAILED_PRECONDITION if a cluster
  // already runs from `data_dir`; CANCELLED if interrupted; if a process exits or is not ready
  // in time, stops the others and returns the error, naming the process, with the last line
  // of its log.
  static absl::StatusOr<std::unique_ptr<LocalCluster>> Start(const LocalClusterOptions& options);

  // Stops whatever still runs (as Stop()) unless Detach()ed.
  ~LocalCluster();

  const ClusterState& state() const { return state_; }

  // A child that exited on its own since the last call: "learner exited with status 1 (see
  // dcs-data/logs/learner.log)". Empty while all run.
  std::string FindExitedProcess();

  // Stops actors, then the learner, then the coordinator, each with SIGTERM and `grace`
  // before SIGKILL; removes cluster.yaml. INTERNAL, naming them, if any process did not exit
  // with status 0 (it crashed earlier, failed, or had to be killed).
  absl::Status Stop(absl::Duration grace);

  // Leaves the processes running on their own (`dcs up -d`).
  void Detach();

 private:
  explicit LocalCluster(LocalClusterOptions options) : options_(std::move(options)) {}

  // `environment`: the child's whole environment; nullopt: ours.
  absl::Status StartProcess(const std::string& name, const std::string& executable,
                            std::vector<std::string> args,
                            std::optional<std::vector<std::string>> environment = std::nullopt);
  absl::Status WaitUntilAllServing();
  // CANCELLED if interrupted, the child's exit if `child` has exited, DEADLINE_EXCEEDED
  // (with `waiting_for`) after `deadline`; else OK: keep waiting.
  absl::Status CheckWaiting(size_t child, absl::Time deadline, absl::string_view waiting_for);
  std::string LogPath(const std::string& name) const;
  // "learner exited with status 69: <last log line> (see <log>)".
  std::string DescribeExited(size_t child, int wait_status) const;

  const LocalClusterOptions options_;
  ClusterState state_;
  std::vector<ChildProcess> children_;  // parallel to state_.processes
};

// Stops the cluster recorded in `data_dir` from another process (`dcs down`): signals a
// foreground supervisor, or stops each process of a detached cluster in reverse order.
// FAILED_PRECONDITION if no cluster is recorded there.
absl::Status StopClusterInDirectory(const std::string& data_dir, absl::Duration grace);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_LOCAL_CLUSTER_H_
