// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_SERVICE_H_
#define DCS_SERVICES_COORDINATOR_SERVICE_H_

// dcs.v1.CoordinatorService over the coordinator library: each method decodes the request,
// calls the library, encodes the reply and converts the status. Thread-safe.
// Borrows the registry (must outlive the service); owns its metrics' registration.

#include <prometheus/counter.h>
#include <prometheus/registry.h>

#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/build_info.h"

namespace dcs::services {

class CoordinatorService final : public v1::CoordinatorService::CallbackService {
 public:
  // Registers dcs_worker_registrations_total{role} in `metrics`, which must outlive the
  // service.
  CoordinatorService(coordinator::WorkerRegistry& registry, BuildInfo build, absl::Time start_time,
                     prometheus::Registry& metrics);

  grpc::ServerUnaryReactor* RegisterWorker(grpc::CallbackServerContext* context,
                                           const v1::RegisterWorkerRequest* request,
                                           v1::RegisterWorkerResponse* response) override;
  grpc::ServerUnaryReactor* Heartbeat(grpc::CallbackServerContext* context,
                                      const v1::HeartbeatRequest* request,
                                      v1::HeartbeatResponse* response) override;
  grpc::ServerUnaryReactor* UnregisterWorker(grpc::CallbackServerContext* context,
                                             const v1::UnregisterWorkerRequest* request,
                                             v1::UnregisterWorkerResponse* response) override;
  grpc::ServerUnaryReactor* GetClusterStatus(grpc::CallbackServerContext* context,
                                             const v1::GetClusterStatusRequest* request,
                                             v1::GetClusterStatusResponse* response) override;

 private:
  coordinator::WorkerRegistry& registry_;
  const v1::BuildInfo build_;
  const absl::Time start_time_;
  prometheus::Counter& learner_registrations_;
  prometheus::Counter& actor_registrations_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_SERVICE_H_
