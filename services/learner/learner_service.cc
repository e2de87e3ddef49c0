// Copyright 2026 The DCS Authors.
#include "services/learner/learner_service.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>

#include "common/status_macros.h"
#include "services/auth.h"
#include "services/grpc_status.h"
#include "services/pieces.h"
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
      rejected_(metrics, "dcs_rollouts_rejected_total",
                "Slots' rollouts refused, by reason (the status code).") {}

grpc::Status LearnerService::GetSlotWork(grpc::ServerContext* context,
                                         const v1::GetSlotWorkRequest* request,
                                         grpc::ServerWriter<v1::GetSlotWorkResponse>* writer) {
  if (absl::Status refused = Authenticate(*context); !refused.ok()) return ToGrpcStatus(refused);
  v1::GetSlotWorkResponse header;
  std::string weights;  // serialised, if the actor lacks them
  auto get = [&]() -> absl::Status {
    const absl::Duration wait =
        std::clamp(DurationFromProto(request->wait()), absl::ZeroDuration(), kMaxWait);
    // A run that loads is work not ready yet: the call waits for it as for work.
    DCS_ASSIGN_OR_RETURN(const std::shared_ptr<learner::RunHost> host,
                         runs_.Find(request->lease().run_id(), request->learner_epoch(), wait));
    DCS_ASSIGN_OR_RETURN(const learner::SlotWork work,
                         host->GetSlotWork(request->lease().slot(), request->lease().epoch(),
                                           request->positioned_at(), wait));
    header.set_ready(work.ready);
    header.set_run_complete(work.run_complete);
    if (!work.ready) return absl::OkStatus();
    header.set_rollout(work.rollout);
    header.set_start_timesteps(work.start_timesteps);
    header.set_n_steps(work.n_steps);
    *header.mutable_publish_time() = TimeToProto(work.published_at);
    if (request->policy_version() != work.rollout) {
      weights = WeightsToProto(*work.weights).SerializeAsString();
    }
    if (work.journal.has_value()) *header.mutable_journal() = JournalToProto(*work.journal);
    return absl::OkStatus();
  };
  if (const absl::Status status = get(); !status.ok()) return ToGrpcStatus(status);
  for (const v1::GetSlotWorkResponse& message :
       CutIntoMessages(std::move(header), weights, &v1::GetSlotWorkResponse::mutable_weights)) {
    if (!writer->Write(message)) break;  // the actor went away; it will ask again
  }
  return grpc::Status::OK;
}

grpc::Status LearnerService::PushRollout(grpc::ServerContext* context,
                                         grpc::ServerReader<v1::PushRolloutRequest>* reader,
                                         v1::PushRolloutResponse* response) {
  if (absl::Status refused = Authenticate(*context); !refused.ok()) {
    rejected_.Count(refused);
    return ToGrpcStatus(refused);
  }
  auto push = [&]() -> absl::Status {
    PieceJoiner<v1::PushRolloutRequest> joiner(&v1::PushRolloutRequest::mutable_data,
                                               "the slot's rollout");
    for (v1::PushRolloutRequest piece; reader->Read(&piece);) {
      DCS_RETURN_IF_ERROR(joiner.Add(std::move(piece)));
    }
    if (!joiner.started()) {
      // Also what a stream looks like here when gRPC ended it for a message over its limit
      // (the actor is told RESOURCE_EXHAUSTED).
      return absl::InvalidArgumentError("no piece of a rollout came: the stream was empty");
    }
    const v1::PushRolloutRequest* request = &joiner.header();
    rollout_bytes_.Observe(static_cast<double>(joiner.payload().size()));
    v1::SlotRollout proto;
    DCS_RETURN_IF_ERROR(joiner.Parse(proto));
    DCS_ASSIGN_OR_RETURN(const std::shared_ptr<learner::RunHost> host,
                         runs_.Find(request->lease().run_id(), request->learner_epoch()));
    DCS_ASSIGN_OR_RETURN(actor::SlotRollout data, SlotRolloutFromProto(proto));
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
  rejected_.Count(status);
  return ToGrpcStatus(status);
}

}  // namespace dcs::services
