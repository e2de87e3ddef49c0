// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_GRID_EVALUATION_CLIENT_H_
#define DCS_SERVICES_CLI_GRID_EVALUATION_CLIENT_H_

// `dcs eval --on-actors`: a run's policy evaluated over a grid of contexts by the cluster's
// actors instead of in this process. The client hands the policy and the grid to the
// coordinator (SubmitGridEvaluation, under a request id of its own, so a retry makes no second
// grid), which makes one evaluation job per cell; actors evaluate their share of the cells as
// `dcs eval` does in its process (actor::EvaluateGridCell), so the returns are the same bit for
// bit; the client asks until every cell is in (GetEvaluation, which the coordinator holds
// until a result comes or a second is up). Thread-safe.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "actor/context_grid.h"
#include "actor/evaluation.h"
#include "actor/policy_weights.h"

namespace dcs::services::cli {

// How far a grid evaluation is: `done` of its `cells` cells are in.
using GridProgress = std::function<void(int done, int cells)>;

// The returns of `weights` in every cell of the grid over `axes` (actor/context_grid.h: the
// base context is run `run_id`'s, as the coordinator stores its config), `episodes` per cell
// from `seed`, in cell order with mean and std filled (actor::SummarizeContext), evaluated by
// the cluster's actors at `address`. Waits as long as the cells take, however long no actor
// takes them (an actor of the run's numeric libraries:
// EvaluationTable::AcquireEvaluationJobs);
// `on_progress`, if set, hears of each change. Every call has the deadline `timeout`; a call
// that fails transiently is retried with backoff until the coordinator has not answered for
// `timeout`. Errors: NOT_FOUND for a run the coordinator does not know; UNAVAILABLE if it
// cannot be reached; INVALID_ARGUMENT for a grid it or an actor refuses; DATA_LOSS for results
// that do not match the grid.
absl::StatusOr<std::vector<actor::ContextResult>> EvaluateGridOnCluster(
    const std::string& address, const std::string& run_id, const actor::PolicyWeights& weights,
    const std::vector<actor::GridAxis>& axes, int episodes, uint64_t seed,
    absl::Duration timeout, const GridProgress& on_progress = nullptr);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_GRID_EVALUATION_CLIENT_H_
