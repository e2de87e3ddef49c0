// Copyright 2026 The DCS Authors.
#include "services/learner/learner_service.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <memory>

#include "common/status_macros.h"
#include "services/grpc_status.h"
#include "services/time_proto.h"
#include "services/trajectory_proto.h"

namespace dcs::services {

LearnerService::LearnerService(HostedRuns& runs, prometheus::Registry& metrics)
    : runs_(runs),
      rollout_bytes_(prometheus::BuildHistogram()
                         .Name("dcs_rollout_bytes")
                         .Help("Bytes of one slot's rollout as received from an actor.")
                         .Register(metrics)
                         .Add({}, prometheus::Histogram::BucketBoundaries{
                                      1 << 10, 1 << 12, 1 << 14, 1 << 16, 1 << 18, 1 << 20,
                                      1 << 22, 1 << 24, 1 << 26})),
      received_(prometheus::BuildCounter()
                    .Name("dcs_rollouts_received_total")
                    .Help("Slots' rollouts taken from actors (retries not counted).")
                    .Register(metrics)
                    .Add({})),
      rejected_(prometheus::BuildCounter()
                    .Name("dcs_rollouts_rejected_total")
                    .Help("Slots' rollouts refused, by reason (the status code).")
                    .Register(metrics)) {}

grpc::Status LearnerService::GetSlotWork(grpc::ServerContext* /*context*/,
                                         const v1::GetSlotWorkRequest* request,
                                         v1::GetSlotWorkResponse* response) {
  auto get = [&]() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const std::shared_ptr<learner::RunHost> host,
                         runs_.Find(request->lease().run_id(), request->learner_epoch()));
    const absl::Duration wait =
        std::clamp(DurationFromProto(request->wait()), absl::ZeroDuration(), kMaxWait);
    DCS_ASSIGN_OR_RETURN(const learner::SlotWork work,
                         host->GetSlotWork(request->lease().slot(), request->lease().epoch(),
                                           request->positioned_at(), wait));
    response->set_ready(work.ready);
    response->set_run_complete(work.run_complete);
    if (!work.ready) return absl::OkStatus();
    response->set_rollout(work.rollout);
    response->set_start_timesteps(work.start_timesteps);
    response->set_n_steps(work.n_steps);
    *response->mutable_publish_time() = TimeToProto(work.published_at);
    if (request->policy_version() != work.rollout) {
      *response->mutable_weights() = WeightsToProto(*work.weights);
    }
    if (work.journal.has_value()) *response->mutable_journal() = JournalToProto(*work.journal);
    return absl::OkStatus();
  };
  return ToGrpcStatus(get());
}

grpc::Status LearnerService::PushRollout(grpc::ServerContext* /*context*/,
                                         const v1::PushRolloutRequest* request,
                                         v1::PushRolloutResponse* response) {
  auto push = [&]() -> absl::Status {
    rollout_bytes_.Observe(static_cast<double>(request->data().ByteSizeLong()));
    DCS_ASSIGN_OR_RETURN(const std::shared_ptr<learner::RunHost> host,
                         runs_.Find(request->lease().run_id(), request->learner_epoch()));
    DCS_ASSIGN_OR_RETURN(actor::SlotRollout data, SlotRolloutFromProto(request->data()));
    if (data.slot != request->lease().slot()) {
      return absl::InvalidArgumentError(absl::StrCat("the rollout of slot ", data.slot,
                                                     " came under the lease of slot ",
                                                     request->lease().slot()));
    }
    DCS_ASSIGN_OR_RETURN(const bool duplicate,
                         host->PushRollout(request->lease().epoch(), request->rollout(),
                                           request->policy_version(), std::move(data)));
    response->set_duplicate(duplicate);
    if (!duplicate) received_.Increment();
    return absl::OkStatus();
  };
  const absl::Status status = push();
  if (!status.ok()) {
    rejected_.Add({{"reason", absl::StatusCodeToString(status.code())}}).Increment();
  }
  return ToGrpcStatus(status);
}

}  // namespace dcs::services
