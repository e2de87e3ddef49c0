// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_SERVICE_MAIN_H_
#define DCS_SERVICES_SERVICE_MAIN_H_

// The main of every DCS service process (dcs-coordinator, dcs-learner, dcs-actor). In order:
// block SIGINT/SIGTERM; parse flags and the optional YAML config; start /metrics; start the
// gRPC server (health, optional reflection, the role's services); let the role start; write
// the port file and print the bound addresses; wait for SIGINT or SIGTERM; stop the role;
// drain the server within --shutdown-grace; exit 0. Any start-up failure is one line on
// stderr and a non-zero exit (services/exit_codes.h).
//
// With port 0 the OS picks a free port; the process prints the one it got on stdout
//   dcs-coordinator listening on 127.0.0.1:41234, metrics on 127.0.0.1:38811
// and, with --port-file, writes them as YAML (grpc_port, metrics_port, pid) atomically.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/status/status.h"
#include "common/library_version.h"
#include "services/build_info.h"
#include "services/metrics_endpoint.h"
#include "services/server.h"

namespace dcs::services {

// What sets one service apart from the others. Called from main's thread only.
class ServiceRole {
 public:
  virtual ~ServiceRole() = default;

  // Adds the role's own flags, bound to its members.
  virtual void AddFlags(CLI::App& app) = 0;

  // After flags are parsed: validates them and builds the role's objects. Errors end the
  // process (INVALID_ARGUMENT for a bad flag value).
  virtual absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) = 0;

  // The gRPC services to serve, borrowed from the role. Called after Init.
  virtual std::vector<ServedService> Services() = 0;

  // Once the server listens on `listen_address` at `server.port()`: start working, and mark
  // the server SERVING when ready to.
  virtual absl::Status Start(Server& server, const std::string& listen_address) = 0;

  // Before the server drains: stop working and leave the cluster.
  virtual void Stop() = 0;
};

struct ServiceDefinition {
  std::string program;      // "dcs-coordinator"
  std::string component;    // "coordinator": logs and dcs_build_info
  std::string description;  // first line of --help
  std::string default_listen;
  std::string default_metrics_listen;
  std::vector<LibraryVersion> libraries;  // of the DCS libraries the process runs
};

// Runs the process; returns its exit code. REQUIRES: called first in main, before any thread
// starts.
int RunService(const ServiceDefinition& definition, ServiceRole& role, int argc, char** argv);

}  // namespace dcs::services

#endif  // DCS_SERVICES_SERVICE_MAIN_H_
