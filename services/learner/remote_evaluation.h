// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEARNER_REMOTE_EVALUATION_H_
#define DCS_SERVICES_LEARNER_REMOTE_EVALUATION_H_

// A hosted run's evaluations, done by actors (docs/architecture.md §9): the learner hands the
// policy that fell due to the coordinator (SubmitEvaluation), which makes one job per evaluation
// context for actors, and asks until every context's returns are in (GetEvaluation, which the
// coordinator holds until they are or a poll interval is up). The returns are those `dcs train`
// computes in one process (actor::EvaluateContext), bit for bit, whichever actors run the jobs.
// Handing a version over is idempotent: a learner that resumes the run from a checkpoint hands it
// over again and gets the results already in.
//
// Thread-safe: a host runs each evaluation on a thread of its own.

#include <memory>

#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "learner/run_host.h"
#include "run/lease_key.h"

namespace dcs::services {

struct RemoteEvaluationOptions {
  absl::Duration poll_interval = absl::Milliseconds(100);
  absl::Duration rpc_timeout = absl::Seconds(10);
};

// An Evaluator for the run held under learner lease `lease`. Its evaluations return CANCELLED
// when the host stops or the lease is lost; DATA_LOSS if the coordinator's results do not
// match the run's contexts and episodes.
learner::Evaluator EvaluateOnActors(std::shared_ptr<v1::CoordinatorService::Stub> coordinator,
                                    run::LeaseKey lease, RemoteEvaluationOptions options);

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEARNER_REMOTE_EVALUATION_H_
