// Copyright 2026 The DCS Authors.
#include "services/learner/learner_service.h"

#include <grpcpp/grpcpp.h>

#include <algorithm>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "services/grpc_status.h"
#include "services/piece_reactors.h"
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
                "Slots' rollouts refused, by reason (the status code).") {
  runs_.OnRunChanged([this](const std::string& run_id) { parked_.Wake(run_id); });
}

LearnerService::~LearnerService() { runs_.OnRunChanged(nullptr); }

namespace {

// The work of the slot `request` names, if it is out: without waiting.
absl::StatusOr<learner::SlotWork> FindSlotWork(HostedRuns& runs,
                                               const v1::GetSlotWorkRequest& request) {
  DCS_ASSIGN_OR_RETURN(const std::shared_ptr<learner::RunHost> host,
                       runs.Find(request.lease().run_id(), request.learner_epoch()));
  return host->GetSlotWork(request.lease().slot(), request.lease().epoch(),
                           request.positioned_at(), absl::ZeroDuration());
}

// GetSlotWork's answer to `request` for `found`: a header and the weights in pieces, if the
// actor lacks them.
absl::StatusOr<std::vector<v1::GetSlotWorkResponse>> SlotWorkMessages(
    const v1::GetSlotWorkRequest& request, const absl::StatusOr<learner::SlotWork>& found) {
  DCS_RETURN_IF_ERROR(found.status());
  const learner::SlotWork& work = *found;
  v1::GetSlotWorkResponse header;
  std::string weights;  // serialised, if the actor lacks them
  header.set_ready(work.ready);
  header.set_run_complete(work.run_complete);
  if (work.ready) {
    header.set_rollout(work.rollout);
    header.set_start_timesteps(work.start_timesteps);
    header.set_n_steps(work.n_steps);
    *header.mutable_publish_time() = TimeToProto(work.published_at);
    if (request.policy_version() != work.rollout) {
      weights = WeightsToProto(*work.weights).SerializeAsString();
    }
    if (work.journal.has_value()) *header.mutable_journal() = JournalToProto(*work.journal);
  }
  return CutIntoMessages(std::move(header), weights, &v1::GetSlotWorkResponse::mutable_weights);
}

}  // namespace

grpc::ServerWriteReactor<v1::GetSlotWorkResponse>* LearnerService::GetSlotWork(
    grpc::CallbackServerContext* context, const v1::GetSlotWorkRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::GetSlotWorkResponse>>(context, [&] {
    auto* writer = new PiecesWriter<v1::GetSlotWorkResponse>();
    // The last attempt's outcome, which the answer encodes (an error until the first attempt,
    // which only a stopping server skips).
    auto found = std::make_shared<absl::StatusOr<learner::SlotWork>>(
        absl::UnavailableError("the learner is stopping"));
    // Whether the call is answered: with work, the run's end or an error. A run that loads is
    // work not ready yet: the call waits for it as for work.
    auto attempt = [this, request, found] {
      *found = FindSlotWork(runs_, *request);
      if (absl::IsUnavailable(found->status())) return false;
      return !found->ok() || (*found)->ready || (*found)->run_complete;
    };
    auto answer = [this, request, found, writer] {
      calls_.Offload([request, found] { return SlotWorkMessages(*request, *found); },
                     [writer](absl::StatusOr<std::vector<v1::GetSlotWorkResponse>> messages) {
                       writer->Start(std::move(messages));
                     });
    };
    const absl::Duration wait =
        std::clamp(DurationFromProto(request->wait()), absl::ZeroDuration(), kMaxWait);
    if (wait <= absl::ZeroDuration()) {
      attempt();
      answer();
    } else {
      parked_.Park(
          request->lease().run_id(), /*question=*/"", absl::Now() + wait,
          [attempt, answer] {
            if (!attempt()) return false;
            answer();
            return true;
          },
          answer);  // as the last attempt left it
    }
    return writer;
  });
}

grpc::ServerReadReactor<v1::PushRolloutRequest>* LearnerService::PushRollout(
    grpc::CallbackServerContext* context, v1::PushRolloutResponse* response) {
  return calls_.Serve<grpc::ServerReadReactor<v1::PushRolloutRequest>>(context, [&] {
    auto push = [this, response](PieceJoiner<v1::PushRolloutRequest>& joiner) -> absl::Status {
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
    return new JoiningReader<v1::PushRolloutRequest>(
        calls_,
        PieceJoiner<v1::PushRolloutRequest>(&v1::PushRolloutRequest::mutable_data,
                                            "the slot's rollout"),
        push, [this](const absl::Status& status) { rejected_.Count(status); });
  });
}

}  // namespace dcs::services
