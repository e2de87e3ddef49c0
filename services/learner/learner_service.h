// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_
#define DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_

// dcs.v1.LearnerService over the runs a learner hosts (services/learner/hosted_runs.h and
// learner/run_host.h): decodes and checks what actors send, waits for work on their behalf,
// encodes the policy. Weights and rollouts travel in pieces (services/pieces.h). The callback
// API, as the coordinator's: every call comes in through ServedCalls (services/served_calls.h),
// which authenticates it; a GetSlotWork that finds no work yet is parked
// (services/parked_calls.h) until its run changes (HostedRuns::OnRunChanged) or its wait is up
// (at most kMaxWait); encoding the policy and decoding a rollout run on the service's work
// pool, never on gRPC's threads.
// Thread-safe. Borrows `runs`, which must outlive the service.
//
// Metrics: dcs_rollout_bytes (histogram of a slot's rollout on the wire),
// dcs_rollouts_received_total, dcs_rollouts_rejected_total{reason}. Training is strictly
// on-policy, so the policy lag of what is taken is 0 by construction: a rollout of a stale
// version is refused, and counted under its reason.

#include <prometheus/counter.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include "absl/time/time.h"
#include "dcs/v1/learner_service.grpc.pb.h"
#include "services/learner/hosted_runs.h"
#include "services/parked_calls.h"
#include "services/refusal_counter.h"
#include "services/served_calls.h"
#include "services/work_pool.h"

namespace dcs::services {

class LearnerService final : public v1::LearnerService::CallbackService {
 public:
  static constexpr absl::Duration kMaxWait = absl::Seconds(5);

  // Watches `runs` (HostedRuns::OnRunChanged) until destroyed.
  LearnerService(HostedRuns& runs, prometheus::Registry& metrics);
  ~LearnerService() override;

  grpc::ServerWriteReactor<v1::GetSlotWorkResponse>* GetSlotWork(
      grpc::CallbackServerContext* context, const v1::GetSlotWorkRequest* request) override;
  grpc::ServerReadReactor<v1::PushRolloutRequest>* PushRollout(
      grpc::CallbackServerContext* context, v1::PushRolloutResponse* response) override;

 private:
  HostedRuns& runs_;
  prometheus::Histogram& rollout_bytes_;
  prometheus::Counter& received_;
  RefusalCounter rejected_;
  // Destroyed after parked_, whose expiries encode their answers here.
  WorkPool pool_{{.threads = 2, .max_queued = 1024}};
  // Unauthenticated calls are counted by gRPC's metrics only: dcs_rollouts_rejected_total
  // counts rollouts refused for what they hold.
  ServedCalls calls_{pool_, nullptr};
  // GetSlotWork calls waiting for work, under their run's id. Destroyed first, answering them.
  ParkedCalls parked_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_
