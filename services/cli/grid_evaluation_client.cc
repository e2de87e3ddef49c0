// Copyright 2026 The DCS Authors.
#include "services/cli/grid_evaluation_client.h"

#include <grpcpp/grpcpp.h>

#include <memory>
#include <utility>

#include "absl/random/random.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "common/status_macros.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/backoff.h"
#include "services/channel.h"
#include "services/cli/run_client.h"
#include "services/evaluation_grid_proto.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/time_proto.h"
#include "services/trajectory_proto.h"
#include "services/unary_call.h"

namespace dcs::services::cli {
namespace {

constexpr BackoffPolicy kRetryBackoff{.initial = absl::Milliseconds(100),
                                      .max = absl::Seconds(1)};
// How long the coordinator may hold an ask while no cell's result comes.
constexpr absl::Duration kPollWait = absl::Seconds(1);

// The cells' results from the coordinator's answer, checked against the grid.
absl::StatusOr<std::vector<actor::ContextResult>> ToCells(
    const std::vector<actor::GridAxis>& axes, int episodes,
    const v1::GetEvaluationResponse& answer) {
  const size_t cells = actor::CellCount(axes);
  if (answer.results_size() != static_cast<int>(cells)) {
    return absl::DataLossError(absl::StrCat("the coordinator has ", answer.results_size(),
                                            " cells' returns; the grid has ", cells));
  }
  std::vector<actor::ContextResult> results;
  for (size_t cell = 0; cell < cells; ++cell) {
    run::ContextReturns returns = ContextReturnsFromProto(answer.results(static_cast<int>(cell)));
    if (static_cast<int>(returns.returns.size()) != episodes) {
      return absl::DataLossError(absl::StrCat("the coordinator has ", returns.returns.size(),
                                              " returns for cell ", cell, "; the grid has ",
                                              episodes, " episodes a cell"));
    }
    // As actor::EvaluateGridCell labels a cell: by its first axis's value.
    actor::ContextResult& result = results.emplace_back(actor::ContextResult{
        .context = {.split = actor::Split::kId, .value = actor::CellValues(axes, cell)[0]},
        .returns = std::move(returns.returns),
        .seconds = returns.seconds});
    actor::SummarizeContext(result);
  }
  return results;
}

}  // namespace

absl::StatusOr<std::vector<actor::ContextResult>> EvaluateGridOnCluster(
    const std::string& address, const std::string& run_id, const actor::PolicyWeights& weights,
    const std::vector<actor::GridAxis>& axes, int episodes, uint64_t seed,
    absl::Duration timeout, const GridProgress& on_progress) {
  const auto coordinator = v1::CoordinatorService::NewStub(OpenChannel(address));
  const std::string peer = absl::StrCat("coordinator ", address);
  absl::Time answered = absl::Now();  // when the coordinator last answered
  const auto keep_trying = [&](const absl::Status&) { return absl::Now() - answered < timeout; };
  const auto unreachable = [&](const absl::Status& status) {
    return absl::UnavailableError(absl::StrCat("the coordinator at ", address,
                                               " has not answered for ",
                                               absl::FormatDuration(timeout), ": ",
                                               status.message()));
  };

  v1::SubmitGridEvaluationRequest header;
  header.set_request_id(NewRequestId());  // the same in every retry: one grid, however many
  header.set_run_id(run_id);
  *header.mutable_grid() = EvaluationGridToProto(axes, seed);
  header.set_episodes(episodes);
  const std::vector<v1::SubmitGridEvaluationRequest> submit =
      CutIntoMessages(std::move(header), WeightsToProto(weights).SerializeAsString(),
                      &v1::SubmitGridEvaluationRequest::mutable_weights);
  v1::SubmitGridEvaluationResponse submitted;
  const absl::Status status = CallClientStreamWithRetries(
      *coordinator, &v1::CoordinatorService::Stub::SubmitGridEvaluation, submit, submitted,
      timeout, peer, kRetryBackoff, keep_trying);
  if (IsTransient(status)) return unreachable(status);
  DCS_RETURN_IF_ERROR(status);

  v1::GetEvaluationRequest get;
  get.set_run_id(run_id);
  get.set_policy_version(submitted.evaluation_key());
  *get.mutable_wait() = DurationToProto(kPollWait);
  int done = -1;
  absl::BitGen random;
  for (int failures = 0;;) {
    v1::GetEvaluationResponse answer;
    const absl::Status asked =
        CallUnary(*coordinator, &v1::CoordinatorService::Stub::GetEvaluation, get, answer,
                  timeout + kPollWait, peer);
    if (asked.ok()) {
      answered = absl::Now();
      failures = 0;
      // Every change is heard, the last one (every cell in) too.
      if (answer.done() != done && on_progress != nullptr) {
        on_progress(answer.done(), answer.contexts());
      }
      if (answer.done() == answer.contexts()) return ToCells(axes, episodes, answer);
      done = answer.done();
      continue;
    }
    if (!IsTransient(asked)) return asked;
    if (!keep_trying(asked)) return unreachable(asked);
    absl::SleepFor(BackoffDelay(kRetryBackoff, ++failures, random));
  }
}

}  // namespace dcs::services::cli
