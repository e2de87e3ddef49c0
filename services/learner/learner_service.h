// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_
#define DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_

// dcs.v1.LearnerService over the runs a learner hosts (services/learner/hosted_runs.h and
// learner/run_host.h): decodes and checks what actors send, waits for work on their behalf,
// encodes the policy. Weights and rollouts travel in pieces (services/pieces.h). The
// synchronous API: GetSlotWork blocks its handler thread while it waits (at most kMaxWait).
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
#include "services/refusal_counter.h"

namespace dcs::services {

class LearnerService final : public v1::LearnerService::Service {
 public:
  static constexpr absl::Duration kMaxWait = absl::Seconds(5);

  LearnerService(HostedRuns& runs, prometheus::Registry& metrics);

  grpc::Status GetSlotWork(grpc::ServerContext* context, const v1::GetSlotWorkRequest* request,
                           grpc::ServerWriter<v1::GetSlotWorkResponse>* writer) override;
  grpc::Status PushRollout(grpc::ServerContext* context,
                           grpc::ServerReader<v1::PushRolloutRequest>* reader,
                           v1::PushRolloutResponse* response) override;

 private:
  HostedRuns& runs_;
  prometheus::Histogram& rollout_bytes_;
  prometheus::Counter& received_;
  RefusalCounter rejected_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEARNER_LEARNER_SERVICE_H_
