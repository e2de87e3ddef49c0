// Copyright 2026 The DCS Authors.
#include "services/cli/local_cluster.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <utility>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "absl/time/clock.h"
#include "common/atomic_file.h"
#include "common/pinned_kernels.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "services/cli/cluster_client.h"
#include "services/port_file.h"

namespace dcs::services::cli {
namespace {

namespace fs = std::filesystem;

constexpr char kStateFile[] = "cluster.yaml";
constexpr char kScrapeTargetsFile[] = "prometheus-targets.yml";
constexpr absl::Duration kPollInterval = absl::Milliseconds(20);

std::string StatePath(const std::string& data_dir) { return (fs::path(data_dir) / kStateFile); }

constexpr char kDefaultDataDir[] = "dcs-data";

std::string PortFilePath(const std::string& data_dir, const std::string& name) {
  return fs::path(data_dir) / "run" / (name + ".ports");
}

// The last non-empty line of a log, to say why a process died.
std::string LastLogLine(const std::string& path) {
  absl::StatusOr<std::string> text = ReadFile(path);
  if (!text.ok()) return "";
  std::vector<absl::string_view> lines = absl::StrSplit(*text, '\n', absl::SkipWhitespace());
  if (lines.empty()) return "";
  absl::string_view last = absl::StripAsciiWhitespace(lines.back());
  return std::string(last.substr(0, 400));
}

absl::Status WriteClusterState(const std::string& data_dir, const ClusterState& state) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "supervisor_pid" << YAML::Value << state.supervisor_pid;
  out << YAML::Key << "coordinator" << YAML::Value << state.coordinator_address;
  out << YAML::Key << "processes" << YAML::Value << YAML::BeginSeq;
  for (const ClusterProcess& process : state.processes) {
    out << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << process.name;
    out << YAML::Key << "executable" << YAML::Value << process.executable;
    out << YAML::Key << "pid" << YAML::Value << process.pid;
    out << YAML::Key << "grpc" << YAML::Value << process.grpc_address;
    out << YAML::Key << "metrics" << YAML::Value << process.metrics_address;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return WriteFileAtomically(StatePath(data_dir), absl::StrCat(out.c_str(), "\n"));
}

// The processes serving /metrics, as a Prometheus file_sd file: a target group per process
// labelled with its role as `job` (the executable's name without "dcs-") and its name as
// `process`. Prometheus rereads the file when it changes.
absl::Status WriteScrapeTargets(const std::string& data_dir, const ClusterState& state) {
  YAML::Emitter out;
  out << YAML::BeginSeq;
  for (const ClusterProcess& process : state.processes) {
    if (process.metrics_address.empty()) continue;  // not bound yet
    out << YAML::BeginMap;
    out << YAML::Key << "targets" << YAML::Value << YAML::Flow << YAML::BeginSeq
        << process.metrics_address << YAML::EndSeq;
    out << YAML::Key << "labels" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "job" << YAML::Value
        << std::string(absl::StripPrefix(process.executable, "dcs-"));
    out << YAML::Key << "process" << YAML::Value << process.name;
    out << YAML::EndMap << YAML::EndMap;
  }
  out << YAML::EndSeq;
  return WriteFileAtomically((fs::path(data_dir) / kScrapeTargetsFile).string(),
                             absl::StrCat(out.c_str(), "\n"));
}

// Removes cluster.yaml, the scrape targets, the token and the port files: the cluster is no
// longer running.
void RemoveClusterFiles(const std::string& data_dir, const ClusterState& state) {
  std::error_code ignored;
  fs::remove(StatePath(data_dir), ignored);
  fs::remove(TokenPath(data_dir), ignored);
  fs::remove(fs::path(data_dir) / kScrapeTargetsFile, ignored);
  for (const ClusterProcess& process : state.processes) {
    fs::remove(PortFilePath(data_dir, process.name), ignored);
  }
}

}  // namespace

std::string TokenPath(const std::string& data_dir) { return fs::path(data_dir) / "token"; }

std::string ProcessLogPath(const std::string& data_dir, const std::string& name) {
  return fs::path(data_dir) / "logs" / (name + ".log");
}

absl::StatusOr<ClusterState> ReadClusterState(const std::string& data_dir) {
  const std::string path = StatePath(data_dir);
  if (!fs::exists(path)) {
    return absl::FailedPreconditionError(
        absl::StrCat("no local cluster is recorded in ", data_dir));
  }
  try {
    const YAML::Node root = YAML::LoadFile(path);
    ClusterState state;
    state.supervisor_pid = root["supervisor_pid"].as<pid_t>();
    state.coordinator_address = root["coordinator"].as<std::string>();
    for (const YAML::Node& node : root["processes"]) {
      state.processes.push_back({.name = node["name"].as<std::string>(),
                                 .executable = node["executable"].as<std::string>(),
                                 .pid = node["pid"].as<pid_t>(),
                                 .grpc_address = node["grpc"].as<std::string>(),
                                 .metrics_address = node["metrics"].as<std::string>()});
    }
    return state;
  } catch (const YAML::Exception& e) {
    return absl::DataLossError(absl::StrCat(path, " is unreadable: ", e.what()));
  }
}

std::string FindDataDir(const fs::path& from) {
  for (fs::path dir = from;; dir = dir.parent_path()) {
    std::error_code error;  // an unreadable directory records nothing
    if (fs::exists(StatePath(dir / kDefaultDataDir), error)) {
      return dir == from ? kDefaultDataDir : (dir / kDefaultDataDir).string();
    }
    if (dir == dir.parent_path()) return kDefaultDataDir;  // the root, or a relative path's top
  }
}

bool IsAnyRunning(const ClusterState& state) {
  for (const ClusterProcess& process : state.processes) {
    if (IsProcessRunning(process.pid, process.executable)) return true;
  }
  return false;
}

absl::StatusOr<std::unique_ptr<LocalCluster>> LocalCluster::Start(
    const LocalClusterOptions& options) {
  if (absl::StatusOr<ClusterState> running = ReadClusterState(options.data_dir);
      running.ok() && IsAnyRunning(*running)) {
    return absl::FailedPreconditionError(
        absl::StrCat("a local cluster already runs from ", options.data_dir, " (coordinator ",
                     running->coordinator_address, "); stop it with `dcs down`"));
  }
  std::error_code error;
  for (const char* sub : {"logs", "run"}) {
    fs::create_directories(fs::path(options.data_dir) / sub, error);
    if (error) {
      return absl::PermissionDeniedError(
          absl::StrCat("cannot create ", (fs::path(options.data_dir) / sub).string(), ": ",
                       error.message()));
    }
  }

  if (!options.token.empty()) {
    DCS_RETURN_IF_ERROR(WriteFileAtomically(TokenPath(options.data_dir), options.token, 0600));
  }
  std::unique_ptr<LocalCluster> cluster(new LocalCluster(options));
  cluster->state_.supervisor_pid = options.detach ? 0 : ::getpid();
  DCS_RETURN_IF_ERROR(cluster->StartProcess(
      "coordinator", "dcs-coordinator",
      {absl::StrCat("--listen=", options.coordinator_listen), "--reflection",
       absl::StrCat("--data-dir=", (fs::path(options.data_dir) / "coordinator").string())}));
  const std::string coordinator = cluster->state_.processes.front().grpc_address;
  cluster->state_.coordinator_address = coordinator;
  // The learner, which links libtorch, starts with the pinned numeric kernels: without them it
  // would start libtorch, then run itself again to set them (learner/torch_runtime.h).
  DCS_RETURN_IF_ERROR(cluster->StartProcess("learner", "dcs-learner",
                                            {absl::StrCat("--coordinator=", coordinator)},
                                            PinnedKernelEnvironment(environ)));
  for (int i = 1; i <= options.actors; ++i) {
    DCS_RETURN_IF_ERROR(cluster->StartProcess(absl::StrCat("actor-", i), "dcs-actor",
                                              {absl::StrCat("--coordinator=", coordinator)}));
  }

  DCS_RETURN_IF_ERROR(cluster->WaitUntilAllServing());
  return cluster;
}

absl::Status LocalCluster::CheckWaiting(size_t child, absl::Time deadline,
                                        absl::string_view waiting_for) {
  if (options_.interrupted()) return absl::CancelledError("start-up interrupted");
  if (std::optional<int> status = children_[child].Poll()) {
    return absl::UnavailableError(DescribeExited(child, *status));
  }
  const std::string& name = state_.processes[child].name;
  if (absl::Now() >= deadline) {
    return absl::DeadlineExceededError(absl::StrCat(name, " ", waiting_for, " within ",
                                                    absl::FormatDuration(options_.start_timeout),
                                                    " (see ", LogPath(name), ")"));
  }
  absl::SleepFor(kPollInterval);
  return absl::OkStatus();
}

absl::Status LocalCluster::WaitUntilAllServing() {
  // A worker is SERVING once registered with the coordinator.
  const absl::Time deadline = absl::Now() + options_.start_timeout;
  for (size_t i = 0; i < state_.processes.size(); ++i) {
    while (true) {
      absl::StatusOr<bool> serving =
          IsServing(state_.processes[i].grpc_address, "", absl::Seconds(1));
      if (serving.ok() && *serving) break;
      DCS_RETURN_IF_ERROR(CheckWaiting(i, deadline, "was not SERVING"));
    }
  }
  return absl::OkStatus();
}

absl::Status LocalCluster::StartProcess(const std::string& name, const std::string& executable,
                                        std::vector<std::string> args,
                                        std::optional<std::vector<std::string>> environment) {
  const std::string port_file = PortFilePath(options_.data_dir, name);
  std::error_code ignored;
  fs::remove(port_file, ignored);
  args.push_back(absl::StrCat("--port-file=", port_file));
  args.push_back("--metrics-listen=127.0.0.1:0");
  if (!options_.token.empty()) {
    args.push_back(absl::StrCat("--token-file=", TokenPath(options_.data_dir)));
  }
  if (options_.tls.enabled()) {
    args.push_back(absl::StrCat("--tls-cert=", options_.tls.certificate));
    args.push_back(absl::StrCat("--tls-key=", options_.tls.key));
    args.push_back(absl::StrCat("--tls-ca=", options_.tls.ca));
    if (!options_.tls.server_name.empty()) {
      args.push_back(absl::StrCat("--tls-server-name=", options_.tls.server_name));
    }
  }
  absl::StatusOr<ChildProcess> child =
      ChildProcess::Start({.path = fs::path(options_.bin_dir) / executable,
                           .args = std::move(args),
                           .output_path = LogPath(name),
                           .environment = std::move(environment),
                           .new_session = options_.detach,
                           .stop_with_parent = !options_.detach});
  if (!child.ok()) return child.status();
  state_.processes.push_back({.name = name, .executable = executable, .pid = child->pid()});
  children_.push_back(*std::move(child));
  // Recorded at once, so that `dcs down` can stop a cluster whose start-up hangs.
  DCS_RETURN_IF_ERROR(WriteClusterState(options_.data_dir, state_));

  const absl::Time deadline = absl::Now() + options_.start_timeout;
  std::optional<BoundPorts> ports;
  while (!(ports = ReadPortFile(port_file))) {
    DCS_RETURN_IF_ERROR(CheckWaiting(children_.size() - 1, deadline, "did not start"));
  }
  state_.processes.back().grpc_address = absl::StrCat("127.0.0.1:", ports->grpc);
  state_.processes.back().metrics_address = absl::StrCat("127.0.0.1:", ports->metrics);
  DCS_RETURN_IF_ERROR(WriteScrapeTargets(options_.data_dir, state_));
  return WriteClusterState(options_.data_dir, state_);
}

std::string LocalCluster::LogPath(const std::string& name) const {
  return ProcessLogPath(options_.data_dir, name);
}

LocalCluster::~LocalCluster() { Stop(absl::Seconds(5)).IgnoreError(); }

std::string LocalCluster::FindExitedProcess() {
  for (size_t i = 0; i < children_.size(); ++i) {
    if (std::optional<int> status = children_[i].Poll()) return DescribeExited(i, *status);
  }
  return "";
}

std::string LocalCluster::DescribeExited(size_t child, int wait_status) const {
  const std::string& name = state_.processes[child].name;
  return absl::StrCat(name, " ", DescribeExit(wait_status), ": ", LastLogLine(LogPath(name)),
                      " (see ", LogPath(name), ")");
}

absl::Status LocalCluster::Stop(absl::Duration grace) {
  if (children_.empty()) return absl::OkStatus();
  std::vector<std::string> unclean;
  for (size_t i = children_.size(); i-- > 0;) {
    const int status = children_[i].Stop(grace);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      unclean.push_back(absl::StrCat(state_.processes[i].name, " ", DescribeExit(status)));
    }
  }
  children_.clear();
  RemoveClusterFiles(options_.data_dir, state_);
  if (unclean.empty()) return absl::OkStatus();
  return absl::InternalError(absl::StrCat("not every process stopped cleanly within ",
                                          absl::FormatDuration(grace), ": ",
                                          absl::StrJoin(unclean, "; ")));
}

void LocalCluster::Detach() {
  for (ChildProcess& child : children_) child.Release();
  children_.clear();
}

absl::Status StopClusterInDirectory(const std::string& data_dir, absl::Duration grace) {
  DCS_ASSIGN_OR_RETURN(const ClusterState state, ReadClusterState(data_dir));
  // A foreground `dcs up` stops its own children in order when told to.
  if (state.supervisor_pid != 0 && IsProcessRunning(state.supervisor_pid, "dcs")) {
    ::kill(state.supervisor_pid, SIGTERM);
    const absl::Time deadline =
        absl::Now() + grace * static_cast<double>(state.processes.size() + 1);
    while (IsProcessRunning(state.supervisor_pid, "dcs") && absl::Now() < deadline) {
      absl::SleepFor(kPollInterval);
    }
  }
  for (auto process = state.processes.rbegin(); process != state.processes.rend(); ++process) {
    StopProcess(process->pid, process->executable, grace);
  }
  RemoveClusterFiles(data_dir, state);
  return absl::OkStatus();
}

}  // namespace dcs::services::cli
