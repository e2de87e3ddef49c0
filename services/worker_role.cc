// Copyright 2026 The DCS Authors.
#include "services/worker_role.h"

#include <unistd.h>

#include <climits>

#include "absl/strings/str_cat.h"
#include "services/address.h"
#include "services/cluster_proto.h"

namespace dcs::services {
namespace {

std::string HostName() {
  char name[HOST_NAME_MAX + 1] = {};
  if (::gethostname(name, sizeof(name)) != 0) return "localhost";
  return name;
}

}  // namespace

void WorkerServiceRole::AddFlags(CLI::App& app) {
  app.add_option("--coordinator", coordinator_address_, "the coordinator's gRPC address host:port")
      ->capture_default_str();
  app.add_option("--advertise-host", advertise_host_,
                 "the host others reach this worker at (default: the --listen host, or this "
                 "machine's name when listening on all interfaces)");
}

absl::Status WorkerServiceRole::Init(MetricsEndpoint& metrics, const BuildInfo& build) {
  metrics_ = &metrics;
  build_ = build;
  return absl::OkStatus();
}

absl::Status WorkerServiceRole::Start(Server& server, const std::string& listen_address) {
  std::string host = advertise_host_;
  if (host.empty()) {
    host = HostOf(listen_address);
    if (host == "0.0.0.0" || host == "[::]" || host.empty()) host = HostName();
  }
  advertised_address_ = JoinHostPort(host, server.port());
  WorkerInfo info{.role = role_,
                  .address = advertised_address_,
                  .hostname = HostName(),
                  .pid = ::getpid(),
                  .version = build_.version,
                  .libraries = build_.libraries};
  WorkerAgentOptions options{
      .coordinator_address = coordinator_address_,
      .worker = WorkerInfoToProto(info),
      .on_membership_change = [&server](bool joined) { server.SetServing(joined); }};
  agent_ = std::make_unique<WorkerAgent>(std::move(options), metrics_->registry());
  return absl::OkStatus();
}

void WorkerServiceRole::Stop() {
  if (agent_ != nullptr) agent_->Stop();
}

}  // namespace dcs::services
