// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_COVERAGE_H_
#define DCS_RUN_COVERAGE_H_

// The coverage diagnostic of a run (docs/reference.md, "Coverage"): which cells of the
// environment's state projections (env/state_projection.h) the training observations fall in, per
// window of RunSpec::Coverage::window environment steps and over the whole run. The learner counts
// them from every rollout it learns from (each step's s_t, reset observations included; step k of
// the run, counting from 1, is in window (k - 1) / window), so a run in one process and the same
// run through the cluster count the same cells. The counts are part of the run's state
// (run/run_checkpoint.h): a run resumed from a checkpoint counts on exactly.
//
// The paper's figures (Appendix D): per window, the cells visited within it, about 6.5 % of
// CartPole's 12^4 in the first 50k steps and under 1 % after; over the run, the cells visited at
// all. Plain data and pure functions; thread-compatible.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/rollout.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/state_projection.h"
#include "run/run_spec.h"

namespace dcs::run {

// One finished window of one projection.
struct CoverageWindow {
  int64_t start_step = 0;  // the window holds steps (start_step, end_step]
  int64_t end_step = 0;
  int64_t visited = 0;    // cells visited in the window
  int64_t new_cells = 0;  // of those, cells no earlier window visited
};

// The words of a bitset of `cells` bits: cell i is bit i % 64 of word i / 64. Defined for every
// count (a checkpoint's, as read from disk, may be any): rounding up by `cells + 63` would
// overflow near the largest int64_t.
inline size_t BitsetWords(int64_t cells) {
  return cells <= 0 ? 0 : static_cast<size_t>(cells / 64 + (cells % 64 != 0 ? 1 : 0));
}

// The counts of one projection so far, in bitsets of BitsetWords(cells) words.
struct ProjectionCounts {
  std::string projection;
  int64_t cells = 0;
  int64_t window = 0;                 // the current window's index
  std::vector<uint64_t> seen;         // cells visited in any window
  std::vector<uint64_t> window_seen;  // cells visited in the current window
  int64_t window_new = 0;             // cells first visited in the current window
  std::vector<CoverageWindow> closed;
};

// The projections an environment declares (`Env::CoverageProjections()`); none for one with
// image observations.
template <typename Env>
const std::vector<env::StateProjection>& EnvironmentProjections();

// The projections `coverage` asks for among `available`, in its order (all of `available` if it
// names none). INVALID_ARGUMENT naming the projection for an unknown name or one named twice,
// and when the environment has none.
absl::StatusOr<std::vector<env::StateProjection>> SelectProjections(
    const RunSpec::Coverage& coverage, const std::vector<env::StateProjection>& available);

// No cell visited yet, for each of `projections`.
std::vector<ProjectionCounts> NewCoverage(const std::vector<env::StateProjection>& projections);

// Counts every step of `rollout`, whose first vector step follows environment step
// `first_step` of the run. REQUIRES: `counts` made by NewCoverage(projections) (or decoded from
// its checkpoint), the rollout's inputs hold every dimension the projections read, steps in
// order across calls.
void RecordCoverage(const std::vector<env::StateProjection>& projections, int64_t window,
                    const actor::Rollout& rollout, int64_t first_step,
                    std::vector<ProjectionCounts>& counts);

// The counts as the evaluation log reports them: every closed window, and the current one up
// to `timesteps` (the run's steps so far) if it has begun.
void AppendCoverage(const std::vector<ProjectionCounts>& counts, int64_t window,
                    int64_t timesteps, v1::EvaluationLog& log);

// Implementation details.

template <typename Env>
const std::vector<env::StateProjection>& EnvironmentProjections() {
  if constexpr (requires { Env::CoverageProjections(); }) {
    return Env::CoverageProjections();
  } else {
    static const auto* none = new std::vector<env::StateProjection>();
    return *none;
  }
}

}  // namespace dcs::run

#endif  // DCS_RUN_COVERAGE_H_
