// Copyright 2026 The DCS Authors.
#include "services/learner/remote_evaluation.h"

#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "actor/evaluation.h"
#include "common/status_macros.h"
#include "services/backoff.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/time_proto.h"
#include "services/trajectory_proto.h"
#include "services/unary_call.h"

namespace dcs::services {
namespace {

constexpr BackoffPolicy kRetryBackoff{.initial = absl::Milliseconds(100),
                                      .max = absl::Seconds(1)};

// The result from the coordinator's answer, checked against the run's contexts and episodes.
absl::StatusOr<actor::EvaluationResult> ToResult(const learner::EvaluationTask& task,
                                                 const v1::GetEvaluationResponse& answer) {
  const std::vector<actor::EvaluationContext>& contexts = task.plan.evaluation_contexts;
  if (answer.results_size() != static_cast<int>(contexts.size())) {
    return absl::DataLossError(absl::StrCat("the coordinator has ", answer.results_size(),
                                            " contexts' returns; the run evaluates ",
                                            contexts.size()));
  }
  actor::EvaluationResult result;
  for (size_t c = 0; c < contexts.size(); ++c) {
    const run::ContextReturns returns =
        ContextReturnsFromProto(answer.results(static_cast<int>(c)));
    if (static_cast<int>(returns.returns.size()) != task.spec.eval_episodes) {
      return absl::DataLossError(absl::StrCat("the coordinator has ", returns.returns.size(),
                                              " returns for context ", c, "; the run evaluates ",
                                              task.spec.eval_episodes, " episodes"));
    }
    result.contexts.push_back(
        {.context = contexts[c], .returns = returns.returns, .seconds = returns.seconds});
  }
  actor::Summarize(result);
  return result;
}

}  // namespace

learner::Evaluator EvaluateOnActors(std::shared_ptr<v1::CoordinatorService::Stub> coordinator,
                                    run::LeaseKey lease, RemoteEvaluationOptions options) {
  return [coordinator = std::move(coordinator), lease = std::move(lease), options](
             const learner::EvaluationTask& task,
             const absl::Notification& stop) -> absl::StatusOr<actor::EvaluationResult> {
    const auto cancelled = [&] {
      return absl::CancelledError(absl::StrCat("the evaluation of policy version ",
                                               task.due.policy_version, " of ", lease.run_id,
                                               " was stopped"));
    };
    v1::SubmitEvaluationRequest header;
    *header.mutable_lease() = LeaseToProto(lease);
    header.set_policy_version(task.due.policy_version);
    header.set_step(task.due.steps.front());
    header.set_contexts(static_cast<int>(task.plan.evaluation_contexts.size()));
    header.set_episodes(task.spec.eval_episodes);
    const std::vector<v1::SubmitEvaluationRequest> submit =
        CutIntoMessages(std::move(header), WeightsToProto(*task.weights).SerializeAsString(),
                        &v1::SubmitEvaluationRequest::mutable_weights);
    v1::SubmitEvaluationResponse submitted;
    const absl::Status status = CallClientStreamWithRetries(
        *coordinator, &v1::CoordinatorService::Stub::SubmitEvaluation, submit, submitted,
        options.rpc_timeout, "coordinator", kRetryBackoff,
        [&](const absl::Status&) { return !stop.HasBeenNotified(); });
    if (stop.HasBeenNotified()) return cancelled();
    if (IsLeaseLost(status)) {
      return absl::CancelledError(absl::StrCat("the run's lease is lost: ", status.message()));
    }
    DCS_RETURN_IF_ERROR(status);

    // The coordinator holds each ask until the evaluation is done or a poll interval is up.
    v1::GetEvaluationRequest get;
    get.set_run_id(lease.run_id);
    get.set_policy_version(task.due.policy_version);
    *get.mutable_wait() = DurationToProto(options.poll_interval);
    while (true) {
      const absl::Time start = absl::Now();
      v1::GetEvaluationResponse answer;
      const absl::Status asked =
          CallUnary(*coordinator, &v1::CoordinatorService::Stub::GetEvaluation, get, answer,
                    options.rpc_timeout, "coordinator");
      if (!asked.ok() && !IsTransient(asked)) return asked;
      if (asked.ok() && answer.done() == answer.contexts()) return ToResult(task, answer);
      // The rest of the interval, if the answer came before it.
      if (stop.WaitForNotificationWithTimeout(options.poll_interval - (absl::Now() - start))) {
        return cancelled();
      }
    }
  };
}

}  // namespace dcs::services
