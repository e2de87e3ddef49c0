// Copyright 2026 The DCS Authors.
#include "services/service_main.h"

#include <signal.h>
#include <unistd.h>

#include <iostream>
#include <memory>
#include <optional>

#include "services/address.h"
#include "services/auth.h"
#include "services/command_line.h"
#include "services/exit_codes.h"
#include "services/log.h"
#include "services/port_file.h"
#include "services/signals.h"

namespace dcs::services {
namespace {

struct CommonFlags {
  std::string listen;
  std::string metrics_listen;
  std::string config;
  std::string port_file;
  LogLevel log_level = LogLevel::kInfo;
  LogFormat log_format = LogFormat::kText;
  bool reflection = false;
  absl::Duration shutdown_grace = absl::Seconds(3);
  std::string token_file;
  TlsFiles tls;
};

void AddCommonFlags(CLI::App& app, CommonFlags& flags) {
  app.add_option("--listen", flags.listen, "gRPC address host:port (port 0 picks a free port)")
      ->capture_default_str();
  app.add_option("--metrics-listen", flags.metrics_listen,
                 "Prometheus /metrics address host:port (port 0 picks a free port)")
      ->capture_default_str();
  app.add_option("--config", flags.config,
                 "YAML file of flag values (keys are long flag names; flags given here win)");
  app.add_option("--port-file", flags.port_file,
                 "write the bound ports here as YAML once serving (grpc_port, metrics_port, pid)");
  AddChoiceOption(app, "--log-level", &flags.log_level, LogLevelNames(),
                  "the least severe events to log");
  AddChoiceOption(app, "--log-format", &flags.log_format, LogFormatNames(),
                  "text, or json (one object per line)");
  app.add_flag("--reflection", flags.reflection,
               "serve gRPC server reflection (for debugging clients such as `buf curl`)");
  AddDurationOption(app, "--shutdown-grace", &flags.shutdown_grace,
                    "on SIGTERM/SIGINT, how long calls in flight may take before cancellation");
  app.add_option("--token-file", flags.token_file,
                 "the cluster's bearer token, required on every call and presented on every "
                 "call made (default: $DCS_TOKEN; neither: no authentication)");
  AddTlsFlags(app, flags.tls);
}

}  // namespace

int RunService(const ServiceDefinition& definition, ServiceRole& role, int argc, char** argv) {
  // Blocked before any thread starts, so only Wait() below ever receives them.
  std::optional<BlockedSignals> signals(std::in_place, std::initializer_list<int>{SIGINT, SIGTERM});

  CLI::App app(definition.description, definition.program);
  CommonFlags flags{.listen = definition.default_listen,
                    .metrics_listen = definition.default_metrics_listen};
  AddCommonFlags(app, flags);
  role.AddFlags(app);
  if (std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;

  ConfigureLogging({.component = definition.component,
                    .min_level = flags.log_level,
                    .format = flags.log_format});

  auto fail = [&](const absl::Status& status) {
    PrintError(definition.program, status.message());
    return ExitCodeFor(status);
  };
  absl::StatusOr<std::string> token = LoadToken(flags.token_file);
  if (!token.ok()) return fail(token.status());
  SetClusterToken(*std::move(token));
  if (absl::Status tls = CheckTlsFiles(flags.tls); !tls.ok()) return fail(tls);
  SetClusterTls(flags.tls);
  const BuildInfo build = ProcessBuildInfo(definition.libraries);
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> metrics =
      MetricsEndpoint::Start(flags.metrics_listen, definition.component, build);
  if (!metrics.ok()) return fail(metrics.status());
  if (absl::Status status = role.Init(**metrics, build); !status.ok()) return fail(status);

  absl::StatusOr<std::unique_ptr<Server>> server =
      Server::Start({.listen_address = flags.listen,
                     .services = role.Services(),
                     .enable_reflection = flags.reflection,
                     .metrics = &(*metrics)->registry()});
  if (!server.ok()) return fail(server.status());
  if (absl::Status status = role.Start(**server, flags.listen); !status.ok()) return fail(status);

  const std::string grpc_address = WithPort(flags.listen, (*server)->port());
  const std::string metrics_address = WithPort(flags.metrics_listen, (*metrics)->port());
  if (!flags.port_file.empty()) {
    absl::Status status =
        WritePortFile(flags.port_file, {.grpc = (*server)->port(), .metrics = (*metrics)->port()});
    if (!status.ok()) {
      role.Stop();
      return fail(status);
    }
  }
  std::cout << definition.program << " listening on " << grpc_address << ", metrics on "
            << metrics_address << std::endl;
  Log(LogLevel::kInfo, "started",
      {{"grpc", grpc_address}, {"metrics", metrics_address}, {"version", build.version}});

  const int signal = signals->Wait();
  // From here a second SIGINT or SIGTERM ends the process at once.
  signals.reset();
  Log(LogLevel::kInfo, "stopping", {{"signal", sigabbrev_np(signal)},
                                    {"grace", absl::FormatDuration(flags.shutdown_grace)}});
  role.Stop();
  (*server)->Shutdown(flags.shutdown_grace);
  Log(LogLevel::kInfo, "stopped");
  return kExitOk;
}

}  // namespace dcs::services
