// Copyright 2026 The DCS Authors.
//
// dcs: the DCS command-line client. `dcs <command> --help` describes each command.
//   dcs up [-d] [--actors N]   start a local cluster (coordinator, learner, actors) on loopback
//   dcs down                   stop the local cluster started from --data-dir
//   dcs status [-o json]       the coordinator's workers: role, address, state, last heartbeat
//   dcs health --addr H:P      exit 0 if the server is SERVING (for probes and scripts)
//   dcs version                this build and the libraries it links
// stdout carries data only; progress and errors go to stderr. Exit codes: README.md.

#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "coordinator/library_versions.h"
#include "env/library_versions.h"
#include "learner/torch_runtime.h"
#include "services/build_info.h"
#include "services/cluster_client.h"
#include "services/command_line.h"
#include "services/exit_codes.h"
#include "services/local_cluster.h"
#include "services/log.h"
#include "services/signals.h"
#include "services/status_format.h"
#include "services/text_table.h"

namespace dcs::services {
namespace {

constexpr char kProgram[] = "dcs";
constexpr char kDefaultCoordinator[] = "127.0.0.1:50051";

struct GlobalFlags {
  std::string addr;  // --addr or DCS_ADDR
  std::string data_dir = "dcs-data";
  absl::Duration timeout = absl::Seconds(5);
  OutputFormat output = OutputFormat::kTable;
};

int Fail(const absl::Status& status) {
  PrintError(kProgram, status.ToString());
  return ExitCodeFor(status);
}

// --addr (or DCS_ADDR), else the local cluster in --data-dir, else the default port.
std::string CoordinatorAddress(const GlobalFlags& flags) {
  if (!flags.addr.empty()) return flags.addr;
  if (absl::StatusOr<ClusterState> state = ReadClusterState(flags.data_dir); state.ok()) {
    return state->coordinator_address;
  }
  return kDefaultCoordinator;
}

int PrintStatus(const GlobalFlags& flags, const std::string& coordinator) {
  absl::StatusOr<v1::GetClusterStatusResponse> status =
      GetClusterStatus(coordinator, flags.timeout);
  if (!status.ok()) return Fail(status.status());
  std::cout << FormatClusterStatus(*status, coordinator, absl::Now(), flags.output) << std::flush;
  return kExitOk;
}

struct UpFlags {
  int actors = 2;
  bool detach = false;
  std::string coordinator_listen = "127.0.0.1:0";
  absl::Duration start_timeout = absl::Seconds(30);
  absl::Duration stop_grace = absl::Seconds(5);
};

int RunUp(const GlobalFlags& flags, const UpFlags& up) {
  // Before any gRPC thread exists, so that only this thread receives them.
  BlockedSignals signals({SIGINT, SIGTERM, SIGCHLD});
  auto interrupted = [&signals] {
    const int signal = signals.Wait(absl::ZeroDuration());
    return signal == SIGINT || signal == SIGTERM;
  };
  LocalClusterOptions options{
      .data_dir = flags.data_dir,
      .bin_dir = std::filesystem::read_symlink("/proc/self/exe").parent_path(),
      .actors = up.actors,
      .coordinator_listen = up.coordinator_listen,
      .detach = up.detach,
      .start_timeout = up.start_timeout,
      .interrupted = interrupted};
  std::cerr << "starting a local cluster: coordinator, learner, " << up.actors
            << " actor(s); logs in " << flags.data_dir << "/logs" << std::endl;
  absl::StatusOr<std::unique_ptr<LocalCluster>> cluster = LocalCluster::Start(options);
  if (!cluster.ok()) return Fail(cluster.status());

  const std::string coordinator = (*cluster)->state().coordinator_address;
  int exit_code = PrintStatus(flags, coordinator);
  if (up.detach) {
    (*cluster)->Detach();
    std::cerr << "the cluster runs in the background; stop it with `dcs down`" << std::endl;
    return exit_code;
  }
  std::cerr << "press Ctrl-C to stop the cluster" << std::endl;
  while (exit_code == kExitOk) {
    const int signal = signals.Wait(absl::Seconds(1));
    if (signal == SIGINT || signal == SIGTERM) break;
    if (std::string exited = (*cluster)->FindExitedProcess(); !exited.empty()) {
      PrintError(kProgram, absl::StrCat(exited, "; stopping the cluster"));
      exit_code = kExitFailure;
    }
  }
  std::cerr << "stopping the cluster" << std::endl;
  if (absl::Status stopped = (*cluster)->Stop(up.stop_grace); !stopped.ok()) {
    PrintError(kProgram, stopped.message());
    return kExitFailure;
  }
  std::cerr << "cluster stopped" << std::endl;
  return exit_code;
}

int RunDown(const GlobalFlags& flags, absl::Duration grace) {
  if (absl::Status status = StopClusterInDirectory(flags.data_dir, grace); !status.ok()) {
    return Fail(status);
  }
  std::cerr << "cluster stopped" << std::endl;
  return kExitOk;
}

int RunHealth(const GlobalFlags& flags, const std::string& service, absl::Duration wait) {
  const std::string address = CoordinatorAddress(flags);
  if (wait > absl::ZeroDuration()) {
    absl::Status serving = WaitUntilServing(address, service, wait);
    std::cout << (serving.ok() ? "SERVING" : "NOT_SERVING") << std::endl;
    return serving.ok() ? kExitOk : Fail(serving);
  }
  absl::StatusOr<bool> serving = IsServing(address, service, flags.timeout);
  if (!serving.ok()) return Fail(serving.status());
  std::cout << (*serving ? "SERVING" : "NOT_SERVING") << std::endl;
  return *serving ? kExitOk : kExitFailure;
}

int RunVersion() {
  BuildInfo build = ProcessBuildInfo(coordinator::LibraryVersions());
  for (const auto& libraries : {env::LibraryVersions(), learner::LibraryVersions()}) {
    build.libraries.insert(build.libraries.end(), libraries.begin(), libraries.end());
  }
  std::vector<std::vector<std::string>> rows = {{"LIBRARY", "VERSION"}};
  for (const LibraryVersion& library : build.libraries) {
    rows.push_back({library.name, library.version});
  }
  std::cout << "dcs " << build.version << "\n\n" << RenderTable(rows) << std::flush;
  return kExitOk;
}

int Main(int argc, char** argv) {
  ConfigureLogging({.component = kProgram});
  CLI::App app("dcs: dynamic context scheduling for reinforcement learning, as a service",
               kProgram);
  app.require_subcommand(0, 1);
  app.fallthrough();  // global flags may follow the command
  GlobalFlags flags;
  app.add_option("--addr", flags.addr,
                 "a server's gRPC address host:port (default: the local cluster's "
                 "coordinator, else 127.0.0.1:50051)")
      ->envname("DCS_ADDR");
  app.add_option("--data-dir", flags.data_dir, "where `dcs up` keeps logs and cluster state")
      ->capture_default_str();
  AddDurationOption(app, "--timeout", &flags.timeout, "deadline of each call to a server");
  AddChoiceOption(app, "-o,--output", &flags.output, OutputFormatNames(),
                  "table, or json (for scripts)");

  UpFlags up_flags;
  CLI::App* up = app.add_subcommand(
      "up", "Start a local cluster (coordinator, learner, actors) as child processes on "
            "loopback; Ctrl-C stops it");
  up->add_option("--actors", up_flags.actors, "number of actors")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  up->add_flag("-d,--detach", up_flags.detach,
               "leave the cluster running in the background; stop it with `dcs down`");
  up->add_option("--coordinator-listen", up_flags.coordinator_listen,
                 "the coordinator's gRPC address (port 0 picks a free port)")
      ->capture_default_str();
  AddDurationOption(*up, "--start-timeout", &up_flags.start_timeout,
                    "how long every process may take to become SERVING");
  AddDurationOption(*up, "--stop-grace", &up_flags.stop_grace,
                    "how long each process may take to stop before it is killed");

  absl::Duration down_grace = absl::Seconds(5);
  CLI::App* down = app.add_subcommand("down", "Stop the local cluster started from --data-dir");
  AddDurationOption(*down, "--stop-grace", &down_grace,
                    "how long each process may take to stop before it is killed");

  CLI::App* status = app.add_subcommand(
      "status", "Show the coordinator's workers: role, id, address, state, last heartbeat");

  std::string health_service;
  absl::Duration health_wait = absl::ZeroDuration();
  CLI::App* health = app.add_subcommand(
      "health", "Ask a server (--addr) whether it is SERVING; exit 0 if so, 1 if not");
  health->add_option("--service", health_service,
                     "a service name such as dcs.v1.CoordinatorService (default: the server)");
  AddDurationOption(*health, "--wait", &health_wait,
                    "keep asking until SERVING or this long has passed");

  CLI::App* version = app.add_subcommand("version", "Show this build and its libraries");

  if (std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  if (up->parsed()) return RunUp(flags, up_flags);
  if (down->parsed()) return RunDown(flags, down_grace);
  if (status->parsed()) return PrintStatus(flags, CoordinatorAddress(flags));
  if (health->parsed()) return RunHealth(flags, health_service, health_wait);
  if (version->parsed()) return RunVersion();
  // Checked here rather than by CLI11, which would report it before an unknown flag.
  PrintError(kProgram, "a command is required: up, down, status, health or version (see --help)");
  return kExitUsage;
}

}  // namespace
}  // namespace dcs::services

int main(int argc, char** argv) { return dcs::services::Main(argc, argv); }
