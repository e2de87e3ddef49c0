// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_WORKER_AGENT_H_
#define DCS_SERVICES_WORKER_AGENT_H_

// A worker's membership in the cluster: a thread that registers with the coordinator and then
// heartbeats at the interval the coordinator asks for. While the coordinator is unreachable it
// retries with exponential backoff and jitter, logging each retry; when a heartbeat returns
// NOT_FOUND (the coordinator restarted) it registers again. Stop() unregisters.
//
// Thread-safe. The destructor stops the agent.
//
// Metrics: dcs_coordinator_connected (1 while registered and heartbeats succeed) and
// dcs_coordinator_rpc_failures_total.

#include <functional>
#include <memory>
#include <string>
#include <thread>

#include <prometheus/counter.h>
#include <prometheus/gauge.h>
#include <prometheus/registry.h>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/backoff.h"

namespace dcs::services {

struct WorkerAgentOptions {
  std::string coordinator_address;  // host:port
  v1::WorkerInfo worker;            // what the worker says about itself
  absl::Duration rpc_timeout = absl::Seconds(2);
  BackoffPolicy backoff;
  // Called whenever the worker joins or leaves the cluster (registered and heartbeating, or
  // not): from the agent's thread, and a last time from Stop(). The worker is ready for work
  // only while joined.
  std::function<void(bool joined)> on_membership_change = [](bool) {};
};

class WorkerAgent {
 public:
  // Starts the agent's thread. Borrows `metrics`, which must outlive the agent.
  WorkerAgent(WorkerAgentOptions options, prometheus::Registry& metrics);
  ~WorkerAgent();
  WorkerAgent(const WorkerAgent&) = delete;
  WorkerAgent& operator=(const WorkerAgent&) = delete;

  // Stops heartbeating, cancels a call in flight and unregisters (bounded by rpc_timeout).
  // Idempotent.
  void Stop();

 private:
  void Run();
  // One attempt each.
  grpc::Status Register();
  grpc::Status Heartbeat();
  // Calls `method` with a deadline, cancellable by Stop().
  template <typename Request, typename Response>
  grpc::Status Call(grpc::Status (v1::CoordinatorService::Stub::*method)(grpc::ClientContext*,
                                                                          const Request&,
                                                                          Response*),
                    const Request& request, Response* response);
  void SetJoined(bool joined);

  // Fixed at construction.
  const WorkerAgentOptions options_;
  std::unique_ptr<v1::CoordinatorService::Stub> stub_;
  prometheus::Gauge& connected_;
  prometheus::Counter& failures_;

  absl::Notification stopping_;
  absl::Mutex mu_;
  grpc::ClientContext* call_in_flight_ ABSL_GUARDED_BY(mu_) = nullptr;
  // Held for the whole of Stop(), so concurrent calls join and unregister once.
  absl::Mutex stop_mu_;

  // Touched only by the agent's thread until it is joined, then by Stop() under stop_mu_.
  std::string worker_id_;
  absl::Duration heartbeat_interval_ = absl::Seconds(1);
  bool joined_ = false;

  std::thread thread_;  // last: starts after everything above is initialised
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_WORKER_AGENT_H_
