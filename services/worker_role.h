// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_WORKER_ROLE_H_
#define DCS_SERVICES_WORKER_ROLE_H_

// The part of dcs-learner and dcs-actor that makes them cluster members: --coordinator and
// --advertise-host flags, and a WorkerAgent that registers and heartbeats. The worker is
// SERVING only while it is registered with the coordinator, so a health probe tells whether it
// can be given work. Confined to main's thread (the agent has its own).

#include <memory>
#include <string>
#include <vector>

#include "common/worker_info.h"
#include "services/service_main.h"
#include "services/worker_agent.h"

namespace dcs::services {

class WorkerServiceRole : public ServiceRole {
 public:
  explicit WorkerServiceRole(WorkerRole role) : role_(role) {}

  void AddFlags(CLI::App& app) override;
  absl::Status Init(MetricsEndpoint& metrics, const BuildInfo& build) override;
  std::vector<ServedService> Services() override { return {}; }
  absl::Status Start(Server& server, const std::string& listen_address) override;
  void Stop() override;

 protected:
  const std::string& coordinator_address() const { return coordinator_address_; }
  // host:port others reach this worker at; set by Start.
  const std::string& advertised_address() const { return advertised_address_; }

 private:
  const WorkerRole role_;
  std::string advertised_address_;
  std::string coordinator_address_ = "127.0.0.1:50051";
  std::string advertise_host_;
  MetricsEndpoint* metrics_ = nullptr;  // borrowed from RunService, which outlives the role's work
  BuildInfo build_;
  std::unique_ptr<WorkerAgent> agent_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_WORKER_ROLE_H_
