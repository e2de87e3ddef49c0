// Copyright 2026 The DCS Authors.
#include "services/cli/cluster_commands.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/text_table.h"
#include "services/auth.h"
#include "services/cli/cluster_client.h"
#include "services/cli/local_cluster.h"
#include "services/cli/status_format.h"
#include "services/command_line.h"
#include "services/exit_codes.h"
#include "services/signals.h"

namespace dcs::services::cli {
namespace {

constexpr char kProgram[] = "dcs";
int PrintStatus(const GlobalFlags& flags, const std::string& coordinator) {
  absl::StatusOr<v1::GetClusterStatusResponse> status =
      GetClusterStatus(coordinator, flags.timeout);
  if (!status.ok()) return FailCommand(status.status());
  std::cout << FormatClusterStatus(*status, coordinator, absl::Now(), flags.output) << std::flush;
  return kExitOk;
}

struct UpFlags {
  int actors = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
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
      // The token given (--token-file, $DCS_TOKEN), else a new one for this cluster.
      .token = ClusterToken().empty() ? NewToken() : ClusterToken(),
      .tls = flags.tls,
      .start_timeout = up.start_timeout,
      .interrupted = interrupted};
  SetClusterToken(options.token);  // for this command's own calls
  std::cerr << "starting a local cluster: coordinator, learner, " << up.actors
            << " actor(s); logs in " << flags.data_dir << "/logs" << std::endl;
  absl::StatusOr<std::unique_ptr<LocalCluster>> cluster = LocalCluster::Start(options);
  if (!cluster.ok()) return FailCommand(cluster.status());

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
    return FailCommand(status);
  }
  std::cerr << "cluster stopped" << std::endl;
  return kExitOk;
}

int RunHealth(const GlobalFlags& flags, const std::string& service, absl::Duration wait) {
  const std::string address = CoordinatorAddress(flags);
  if (wait > absl::ZeroDuration()) {
    absl::Status serving = WaitUntilServing(address, service, wait);
    std::cout << (serving.ok() ? "SERVING" : "NOT_SERVING") << std::endl;
    return serving.ok() ? kExitOk : FailCommand(serving);
  }
  absl::StatusOr<bool> serving = IsServing(address, service, flags.timeout);
  if (!serving.ok()) return FailCommand(serving.status());
  std::cout << (*serving ? "SERVING" : "NOT_SERVING") << std::endl;
  return *serving ? kExitOk : kExitFailure;
}

}  // namespace

std::vector<CliCommand> AddClusterCommands(CLI::App& dcs, const GlobalFlags& flags) {
  auto up_flags = std::make_shared<UpFlags>();
  CLI::App* up = dcs.add_subcommand(
      "up", "Start a local cluster (coordinator, learner, actors) as child processes on "
            "loopback; Ctrl-C stops it");
  up->add_option("--actors", up_flags->actors, "number of actors (default: one per core)")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  up->add_flag("-d,--detach", up_flags->detach,
               "leave the cluster running in the background; stop it with `dcs down`");
  up->add_option("--coordinator-listen", up_flags->coordinator_listen,
                 "the coordinator's gRPC address (port 0 picks a free port)")
      ->capture_default_str();
  AddDurationOption(*up, "--start-timeout", &up_flags->start_timeout,
                    "how long every process may take to become SERVING");
  AddDurationOption(*up, "--stop-grace", &up_flags->stop_grace,
                    "how long each process may take to stop before it is killed");

  auto down_grace = std::make_shared<absl::Duration>(absl::Seconds(5));
  CLI::App* down = dcs.add_subcommand("down", "Stop the local cluster started from --data-dir");
  AddDurationOption(*down, "--stop-grace", down_grace.get(),
                    "how long each process may take to stop before it is killed");

  CLI::App* status = dcs.add_subcommand(
      "status", "Show the coordinator's workers: role, id, address, state, last heartbeat");

  auto health_service = std::make_shared<std::string>();
  auto health_wait = std::make_shared<absl::Duration>(absl::ZeroDuration());
  CLI::App* health = dcs.add_subcommand(
      "health", "Ask a server (--addr) whether it is SERVING; exit 0 if so, 1 if it answers "
                "NOT_SERVING, 69 if it does not answer");
  health->add_option("--service", *health_service,
                     "a service name such as dcs.v1.CoordinatorService (default: the server)");
  AddDurationOption(*health, "--wait", health_wait.get(),
                    "keep asking until SERVING or this long has passed");

  return {
      {up, [&flags, up_flags] { return RunUp(flags, *up_flags); }},
      {down, [&flags, down_grace] { return RunDown(flags, *down_grace); }},
      {status, [&flags] { return PrintStatus(flags, CoordinatorAddress(flags)); }, kEveryFormat},
      {health,
       [&flags, health_service, health_wait] {
         return RunHealth(flags, *health_service, *health_wait);
       }},
  };
}

}  // namespace dcs::services::cli
