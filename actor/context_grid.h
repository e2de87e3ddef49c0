// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_CONTEXT_GRID_H_
#define DCS_ACTOR_CONTEXT_GRID_H_

// A policy's returns over a grid of contexts (`dcs eval`): one or two context features, each
// over evenly spaced values, every other feature at a base context; in each cell, the paper's
// evaluation protocol (actor/evaluation.h): deterministic episodes, episode i of cell c reset
// as the run's evaluation context c's would be (StreamSeed(seed, "eval", {c}), episode i). The
// returns are the same whatever the number of threads. Thread-safe (pure functions; each
// thread acts with a network of its own).

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "actor/policy_weights.h"
#include "common/status_macros.h"
#include "env/context_feature.h"
#include "env/dynamic_context_env.h"

namespace dcs::actor {

// `count` values of a feature, evenly spaced from `low` to `high` (both included; `low` alone
// when count is 1).
struct GridAxis {
  int feature = 0;  // index into the environment's ContextSpace
  std::string name;
  double low = 0;
  double high = 0;
  int count = 1;

  double value(int i) const {
    return count == 1 ? low : low + (high - low) * i / (count - 1);
  }
};

// The axis `text` spells as FEATURE=LOW:HIGH:N (`--grid length=0.1:2:40`). INVALID_ARGUMENT
// naming the text for a malformed spelling, N < 1, LOW > HIGH or (count 1) LOW != HIGH; for an
// unknown feature or a value outside its physical bounds, the message `dcs train` gives.
absl::StatusOr<GridAxis> ParseGridAxis(const env::ContextSpace& space, absl::string_view text);

// The axis of `count` values of feature `name` from `low` to `high` (as a grid travels to the
// cluster's actors): INVALID_ARGUMENT as ParseGridAxis, naming the axis.
absl::StatusOr<GridAxis> MakeGridAxis(const env::ContextSpace& space, std::string name,
                                      double low, double high, int count);

// The cells of a grid over `axes` (one or two), the first axis varying fastest: cell
// i0 + count0 * i1 sets axes[0] to its value i0 and axes[1] to its value i1.
size_t CellCount(const std::vector<GridAxis>& axes);
std::vector<double> CellValues(const std::vector<GridAxis>& axes, size_t cell);

// The options cell `cell` of the grid over `axes` is evaluated with: `base`'s context (Env's
// defaults if empty) with the cell's values, its observation mode and observed features.
// INVALID_ARGUMENT if Env refuses the cell's context.
template <typename Env>
absl::StatusOr<env::DynamicContextOptions> GridCellOptions(const env::DynamicContextOptions& base,
                                                           const std::vector<GridAxis>& axes,
                                                           size_t cell);

// The returns of cell `cell` of the grid over `axes` (`options`: its GridCellOptions): the
// protocol's episodes for the cell's context as evaluation context number `cell`.
template <typename Env>
absl::StatusOr<ContextResult> EvaluateGridCell(Policy& policy,
                                               const env::DynamicContextOptions& options,
                                               const std::vector<GridAxis>& axes, size_t cell,
                                               int episodes, uint64_t seed);

// The returns of `weights`'s deterministic policy in every cell of the grid over `axes`, in cell
// order (ContextResult::context.value: the first axis's value): `base` gives the other
// features' values, the observation mode and the observed features (its pools and schedules
// are ignored). `threads` (at least 1) evaluate cells at once. INVALID_ARGUMENT, before any
// episode, if a cell's context is not valid for Env; as PolicyNetwork::Create for weights.
template <typename Env>
absl::StatusOr<std::vector<ContextResult>> EvaluateGrid(const PolicyWeights& weights,
                                                        const env::DynamicContextOptions& base,
                                                        const std::vector<GridAxis>& axes,
                                                        int episodes, uint64_t seed,
                                                        int threads);

// Implementation details.

template <typename Env>
absl::StatusOr<env::DynamicContextOptions> GridCellOptions(const env::DynamicContextOptions& base,
                                                           const std::vector<GridAxis>& axes,
                                                           size_t cell) {
  env::DynamicContextOptions options{
      .context = base.context.empty() ? Env::Features().Defaults() : base.context,
      .observe = base.observe,
      .observed_features = base.observed_features};
  const std::vector<double> values = CellValues(axes, cell);
  for (size_t a = 0; a < axes.size(); ++a) options.context[axes[a].feature] = values[a];
  DCS_RETURN_IF_ERROR(Env::ValidateContext(options.context));
  return options;
}

template <typename Env>
absl::StatusOr<ContextResult> EvaluateGridCell(Policy& policy,
                                               const env::DynamicContextOptions& options,
                                               const std::vector<GridAxis>& axes, size_t cell,
                                               int episodes, uint64_t seed) {
  DCS_ASSIGN_OR_RETURN(ContextResult result,
                       EvaluateContext<Env>(policy, options, axes[0].feature,
                                            {.split = Split::kId,
                                             .value = options.context[axes[0].feature]},
                                            cell, episodes, seed));
  SummarizeContext(result);
  return result;
}

template <typename Env>
absl::StatusOr<std::vector<ContextResult>> EvaluateGrid(const PolicyWeights& weights,
                                                        const env::DynamicContextOptions& base,
                                                        const std::vector<GridAxis>& axes,
                                                        int episodes, uint64_t seed,
                                                        int threads) {
  const size_t cells = CellCount(axes);
  // Every cell's options, checked before any episode.
  std::vector<env::DynamicContextOptions> options;
  for (size_t cell = 0; cell < cells; ++cell) {
    DCS_ASSIGN_OR_RETURN(options.emplace_back(), GridCellOptions<Env>(base, axes, cell));
  }
  DCS_RETURN_IF_ERROR(PolicyNetwork::Create(weights).status());

  std::vector<ContextResult> results(cells);
  std::atomic<size_t> next{0};
  absl::Mutex mu;
  absl::Status first_error;
  const auto work = [&] {
    PolicyNetwork policy = *PolicyNetwork::Create(weights);
    for (size_t cell = next++; cell < cells; cell = next++) {
      absl::StatusOr<ContextResult> result =
          EvaluateGridCell<Env>(policy, options[cell], axes, cell, episodes, seed);
      if (!result.ok()) {
        absl::MutexLock lock(&mu);
        if (first_error.ok()) first_error = result.status();
        next = cells;  // the others stop after their cell
        return;
      }
      results[cell] = *std::move(result);
    }
  };
  std::vector<std::thread> workers;
  const size_t helpers = std::min<size_t>(std::max(threads, 1), cells) - 1;
  for (size_t t = 0; t < helpers; ++t) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
  DCS_RETURN_IF_ERROR(first_error);
  return results;
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_CONTEXT_GRID_H_
