// Copyright 2026 The DCS Authors.
#include "services/worker_agent.h"

#include <grpcpp/grpcpp.h>

#include <utility>

#include "absl/random/random.h"
#include "absl/strings/str_cat.h"
#include "services/channel.h"
#include "services/grpc_status.h"
#include "services/log.h"
#include "services/time_proto.h"

namespace dcs::services {
WorkerAgent::WorkerAgent(WorkerAgentOptions options, prometheus::Registry& metrics)
    : options_(std::move(options)),
      stub_(v1::CoordinatorService::NewStub(OpenChannel(options_.coordinator_address))),
      connected_(prometheus::BuildGauge()
                     .Name("dcs_coordinator_connected")
                     .Help("1 while this worker is registered with the coordinator and its "
                           "heartbeats succeed, else 0.")
                     .Register(metrics)
                     .Add({})),
      failures_(prometheus::BuildCounter()
                    .Name("dcs_coordinator_rpc_failures_total")
                    .Help("Failed registration and heartbeat calls to the coordinator.")
                    .Register(metrics)
                    .Add({})),
      thread_([this] { Run(); }) {}

WorkerAgent::~WorkerAgent() { Stop(); }

void WorkerAgent::Stop() {
  absl::MutexLock stop_lock(&stop_mu_);
  {
    absl::MutexLock lock(&mu_);
    if (!stopping_.HasBeenNotified()) stopping_.Notify();
    if (call_in_flight_ != nullptr) call_in_flight_->TryCancel();
  }
  if (thread_.joinable()) thread_.join();
  if (worker_id_.empty()) return;
  // The coordinator would notice the silence anyway; leaving says it was a clean shutdown.
  grpc::ClientContext context;
  SetTimeout(context, options_.rpc_timeout);
  v1::UnregisterWorkerRequest request;
  request.set_worker_id(worker_id_);
  v1::UnregisterWorkerResponse response;
  const grpc::Status status = stub_->UnregisterWorker(&context, request, &response);
  if (status.ok()) {
    Log(LogLevel::kInfo, "left the cluster", {{"worker_id", worker_id_}});
  } else {
    Log(LogLevel::kWarning, "could not unregister from the coordinator",
        {{"worker_id", worker_id_}, {"error", FromGrpcStatus(status).ToString()}});
  }
  worker_id_.clear();
  SetJoined(false);
}

void WorkerAgent::Run() {
  absl::BitGen random;
  int failures = 0;
  while (!stopping_.HasBeenNotified()) {
    const bool registering = worker_id_.empty();
    const grpc::Status status = registering ? Register() : Heartbeat();
    absl::Duration wait = heartbeat_interval_;
    if (stopping_.HasBeenNotified()) break;
    if (status.ok()) {
      if (registering) {
        Log(LogLevel::kInfo, "registered with the coordinator",
            {{"worker_id", worker_id_}, {"coordinator", options_.coordinator_address}});
      } else if (failures > 0) {
        Log(LogLevel::kInfo, "coordinator reachable again",
            {{"coordinator", options_.coordinator_address}});
      }
      failures = 0;
      SetJoined(true);
    } else if (!registering && status.error_code() == grpc::StatusCode::NOT_FOUND) {
      Log(LogLevel::kWarning, "the coordinator no longer knows this worker; registering again",
          {{"worker_id", worker_id_}});
      worker_id_.clear();
      SetJoined(false);
      wait = absl::ZeroDuration();
    } else {
      ++failures;
      failures_.Increment();
      SetJoined(false);
      wait = BackoffDelay(options_.backoff, failures, random);
      Log(LogLevel::kWarning,
          registering ? "coordinator unreachable; retrying registration with backoff"
                      : "heartbeat failed; retrying with backoff",
          {{"coordinator", options_.coordinator_address},
           {"error", FromGrpcStatus(status).ToString()},
           {"attempt", failures},
           {"retry_in", absl::FormatDuration(absl::Trunc(wait, absl::Milliseconds(1)))}});
    }
    stopping_.WaitForNotificationWithTimeout(wait);
  }
}

template <typename Request, typename Response>
grpc::Status WorkerAgent::Call(
    grpc::Status (v1::CoordinatorService::Stub::*method)(grpc::ClientContext*, const Request&,
                                                         Response*),
    const Request& request, Response* response) {
  grpc::ClientContext context;
  SetTimeout(context, options_.rpc_timeout);
  {
    absl::MutexLock lock(&mu_);
    if (stopping_.HasBeenNotified()) return grpc::Status::CANCELLED;
    call_in_flight_ = &context;
  }
  grpc::Status status = (stub_.get()->*method)(&context, request, response);
  absl::MutexLock lock(&mu_);
  call_in_flight_ = nullptr;
  return status;
}

grpc::Status WorkerAgent::Register() {
  v1::RegisterWorkerRequest request;
  *request.mutable_worker() = options_.worker;
  v1::RegisterWorkerResponse response;
  const grpc::Status status =
      Call(&v1::CoordinatorService::Stub::RegisterWorker, request, &response);
  if (status.ok()) {
    worker_id_ = response.worker_id();
    const absl::Duration interval = DurationFromProto(response.heartbeat_interval());
    if (interval > absl::ZeroDuration()) heartbeat_interval_ = interval;
  }
  return status;
}

grpc::Status WorkerAgent::Heartbeat() {
  v1::HeartbeatRequest request;
  request.set_worker_id(worker_id_);
  v1::HeartbeatResponse response;
  return Call(&v1::CoordinatorService::Stub::Heartbeat, request, &response);
}

void WorkerAgent::SetJoined(bool joined) {
  if (joined == joined_) return;
  joined_ = joined;
  connected_.Set(joined ? 1 : 0);
  options_.on_membership_change(joined);
}

}  // namespace dcs::services
