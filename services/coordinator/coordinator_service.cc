// Copyright 2026 The DCS Authors.
#include "services/coordinator/coordinator_service.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "services/cluster_proto.h"
#include "services/coordinator/record_proto.h"
#include "services/grpc_status.h"
#include "services/log.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

prometheus::Family<prometheus::Counter>& RegistrationsFamily(prometheus::Registry& metrics) {
  return prometheus::BuildCounter()
      .Name("dcs_worker_registrations_total")
      .Help("Worker registrations accepted by the coordinator, by role.")
      .Register(metrics);
}

prometheus::Family<prometheus::Counter>& LeasesFamily(prometheus::Registry& metrics) {
  return prometheus::BuildCounter()
      .Name("dcs_leases_granted_total")
      .Help("Leases granted by the coordinator, by kind (run: to a learner; slot and "
            "evaluation: to an actor).")
      .Register(metrics);
}

prometheus::Family<prometheus::Gauge>& WatchersFamily(prometheus::Registry& metrics) {
  return prometheus::BuildGauge()
      .Name("dcs_watchers")
      .Help("WatchRun and WatchSweep streams open now, by kind (run, sweep).")
      .Register(metrics);
}

}  // namespace

CoordinatorService::CoordinatorService(coordinator::WorkerRegistry& registry, RunStorage runs,
                                       BuildInfo build, absl::Time start_time,
                                       prometheus::Registry& metrics)
    : registry_(registry),
      runs_(std::move(runs)),
      completed_logs_(runs_.data_dir),
      build_(BuildInfoToProto(build)),
      start_time_(start_time),
      learner_registrations_(RegistrationsFamily(metrics).Add({{"role", "learner"}})),
      actor_registrations_(RegistrationsFamily(metrics).Add({{"role", "actor"}})),
      learner_leases_(LeasesFamily(metrics).Add({{"kind", "run"}})),
      slot_leases_(LeasesFamily(metrics).Add({{"kind", "slot"}})),
      evaluation_leases_(LeasesFamily(metrics).Add({{"kind", "evaluation"}})),
      runs_failed_(prometheus::BuildCounter()
                       .Name("dcs_runs_failed_total")
                       .Help("Runs that entered the failed state (their learner finished them "
                             "so) since the coordinator started.")
                       .Register(metrics)
                       .Add({})),
      rejected_(metrics, "dcs_requests_rejected_total",
                "Requests the coordinator refused, by reason (the status code)."),
      run_watchers_(WatchersFamily(metrics).Add({{"kind", "run"}})),
      sweep_watchers_(WatchersFamily(metrics).Add({{"kind", "sweep"}})) {}

int CoordinatorService::AliveActors() const {
  const std::vector<coordinator::WorkerRecord> workers = registry_.List(absl::Now());
  return static_cast<int>(std::count_if(workers.begin(), workers.end(), [](const auto& worker) {
    return worker.info.role == WorkerRole::kActor &&
           worker.state == coordinator::WorkerState::kAlive;
  }));
}

std::string CoordinatorService::EvaluationTopic(absl::string_view run_id,
                                                int64_t policy_version) {
  return absl::StrCat("evaluation ", run_id, "@", policy_version);
}

absl::Time ParkingDeadline(const grpc::CallbackServerContext& context, absl::Duration wait) {
  constexpr absl::Duration kMaxWait = absl::Seconds(10);
  constexpr absl::Duration kAnswerMargin = absl::Milliseconds(100);
  absl::Time deadline = absl::Now() + std::min(wait, kMaxWait);
  if (context.deadline() != std::chrono::system_clock::time_point::max()) {
    deadline = std::min(deadline, absl::FromChrono(context.deadline()) - kAnswerMargin);
  }
  return deadline;
}

void CoordinatorService::AnswerOrPark(const grpc::CallbackServerContext& context,
                                      const google::protobuf::Duration& wait, std::string topic,
                                      std::string question,
                                      std::function<absl::StatusOr<bool>()> attempt,
                                      std::function<void(const absl::Status&)> answer) {
  auto counted = [this, answer = std::move(answer)](const absl::Status& status) {
    rejected_.Count(status);
    answer(status);
  };
  const absl::Duration asked = DurationFromProto(wait);
  if (asked <= absl::ZeroDuration()) {
    calls_.Offload([attempt = std::move(attempt)] { return attempt().status(); }, counted);
    return;
  }
  parked_.Park(
      std::move(topic), std::move(question), ParkingDeadline(context, asked),
      [attempt = std::move(attempt), counted] {
        const absl::StatusOr<bool> found = attempt();
        if (found.ok() && !*found) return false;
        counted(found.status());
        return true;
      },
      [counted] { counted(absl::OkStatus()); });  // as the last attempt left it
}

grpc::ServerUnaryReactor* CoordinatorService::AnswerOrPark(
    grpc::CallbackServerContext* context, const google::protobuf::Duration& wait,
    std::string topic, std::string question, std::function<absl::StatusOr<bool>()> attempt) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  AnswerOrPark(*context, wait, std::move(topic), std::move(question), std::move(attempt),
               [reactor](const absl::Status& status) { reactor->Finish(ToGrpcStatus(status)); });
  return reactor;
}

void CoordinatorService::RunsChanged() {
  watchers_.NotifyAll();
  for (const char* topic : {kRunsTopic, kSlotsTopic, kEvaluationJobsTopic}) parked_.Wake(topic);
}

grpc::ServerUnaryReactor* CoordinatorService::RegisterWorker(
    grpc::CallbackServerContext* context, const v1::RegisterWorkerRequest* request,
    v1::RegisterWorkerResponse* response) {
  return calls_.Inline(context, [&]() -> absl::Status {
    absl::StatusOr<WorkerInfo> info = WorkerInfoFromProto(request->worker());
    if (!info.ok()) return info.status();
    const WorkerRole role = info->role;
    const std::string address = info->address;
    absl::StatusOr<std::string> id = registry_.Register(*std::move(info), absl::Now());
    if (!id.ok()) return id.status();

    (role == WorkerRole::kLearner ? learner_registrations_ : actor_registrations_).Increment();
    Log(LogLevel::kInfo, "worker registered",
        {{"worker_id", *id}, {"role", WorkerRoleName(role)}, {"address", address}});
    response->set_worker_id(*id);
    *response->mutable_heartbeat_interval() =
        DurationToProto(registry_.options().heartbeat_interval);
    return absl::OkStatus();
  });
}

grpc::ServerUnaryReactor* CoordinatorService::Heartbeat(grpc::CallbackServerContext* context,
                                                        const v1::HeartbeatRequest* request,
                                                        v1::HeartbeatResponse* /*response*/) {
  return calls_.Inline(context,
                       [&] { return registry_.Heartbeat(request->worker_id(), absl::Now()); });
}

grpc::ServerUnaryReactor* CoordinatorService::UnregisterWorker(
    grpc::CallbackServerContext* context, const v1::UnregisterWorkerRequest* request,
    v1::UnregisterWorkerResponse* /*response*/) {
  return calls_.Inline(context, [&] {
    absl::Status status = registry_.Unregister(request->worker_id(), absl::Now());
    if (status.ok()) Log(LogLevel::kInfo, "worker left", {{"worker_id", request->worker_id()}});
    return status;
  });
}

grpc::ServerUnaryReactor* CoordinatorService::GetClusterStatus(
    grpc::CallbackServerContext* context, const v1::GetClusterStatusRequest* /*request*/,
    v1::GetClusterStatusResponse* response) {
  return calls_.Inline(context, [&] {
    *response->mutable_coordinator_build() = build_;
    *response->mutable_coordinator_start_time() = TimeToProto(start_time_);
    for (const coordinator::WorkerRecord& record : registry_.List(absl::Now())) {
      *response->add_workers() = WorkerToProto(record);
    }
    return absl::OkStatus();
  });
}

}  // namespace dcs::services
