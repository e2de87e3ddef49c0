// Copyright 2026 The DCS Authors.
#include "run/coverage.h"

#include <algorithm>
#include <bit>
#include <span>

#include "absl/strings/str_cat.h"

namespace dcs::run {
namespace {

int64_t CountBits(const std::vector<uint64_t>& bits) {
  int64_t count = 0;
  for (uint64_t word : bits) count += std::popcount(word);
  return count;
}

// Ends the current window of `counts` and starts the next.
void CloseWindow(int64_t window, ProjectionCounts& counts) {
  counts.closed.push_back({.start_step = counts.window * window,
                           .end_step = (counts.window + 1) * window,
                           .visited = CountBits(counts.window_seen),
                           .new_cells = counts.window_new});
  std::fill(counts.window_seen.begin(), counts.window_seen.end(), 0);
  counts.window_new = 0;
  ++counts.window;
}

void Visit(int64_t cell, ProjectionCounts& counts) {
  const uint64_t bit = uint64_t{1} << (cell % 64);
  uint64_t& seen = counts.seen[cell / 64];
  if ((seen & bit) == 0) {
    seen |= bit;
    ++counts.window_new;
  }
  counts.window_seen[cell / 64] |= bit;
}

}  // namespace

absl::StatusOr<std::vector<env::StateProjection>> SelectProjections(
    const RunSpec::Coverage& coverage, const std::vector<env::StateProjection>& available) {
  if (available.empty()) {
    return absl::InvalidArgumentError(
        "the environment has no state projections to count coverage in (its observations are "
        "images)");
  }
  if (coverage.projections.empty()) return available;
  std::vector<env::StateProjection> selected;
  for (const std::string& name : coverage.projections) {
    auto named = [&](const env::StateProjection& p) { return p.name == name; };
    if (std::any_of(selected.begin(), selected.end(), named)) {
      return absl::InvalidArgumentError(absl::StrCat("projection '", name, "' is named twice"));
    }
    auto it = std::find_if(available.begin(), available.end(), named);
    if (it == available.end()) {
      std::string known;
      for (const env::StateProjection& p : available) {
        absl::StrAppend(&known, known.empty() ? "" : ", ", p.name);
      }
      return absl::InvalidArgumentError(
          absl::StrCat("unknown projection '", name, "' (the environment has: ", known, ")"));
    }
    selected.push_back(*it);
  }
  return selected;
}

std::vector<ProjectionCounts> NewCoverage(const std::vector<env::StateProjection>& projections) {
  std::vector<ProjectionCounts> counts;
  for (const env::StateProjection& projection : projections) {
    const int64_t cells = env::NumCells(projection);
    const size_t words = BitsetWords(cells);
    counts.push_back({.projection = projection.name,
                      .cells = cells,
                      .seen = std::vector<uint64_t>(words),
                      .window_seen = std::vector<uint64_t>(words)});
  }
  return counts;
}

void RecordCoverage(const std::vector<env::StateProjection>& projections, int64_t window,
                    const actor::Rollout& rollout, int64_t first_step,
                    std::vector<ProjectionCounts>& counts) {
  const int64_t transitions = static_cast<int64_t>(rollout.num_steps) * rollout.num_envs;
  if (transitions == 0) return;
  const size_t input_size = rollout.inputs.size() / static_cast<size_t>(transitions);
  for (int64_t i = 0; i < transitions; ++i) {
    // Transition i is step t = i / num_envs of slot e = i % num_envs: run step first + i + 1.
    const int64_t step_window = (first_step + i) / window;
    const std::span<const float> input(rollout.inputs.data() + i * input_size, input_size);
    for (size_t p = 0; p < projections.size(); ++p) {
      while (counts[p].window < step_window) CloseWindow(window, counts[p]);
      Visit(env::CellOf(projections[p], input), counts[p]);
    }
  }
}

void AppendCoverage(const std::vector<ProjectionCounts>& counts, int64_t window,
                    int64_t timesteps, v1::EvaluationLog& log) {
  for (const ProjectionCounts& projection : counts) {
    v1::ProjectionCoverage& out = *log.add_coverage();
    out.set_projection(projection.projection);
    out.set_cells(projection.cells);
    auto add = [&](const CoverageWindow& w) {
      v1::CoverageWindow& to = *out.add_windows();
      to.set_start_step(w.start_step);
      to.set_end_step(w.end_step);
      to.set_visited(w.visited);
      to.set_new_cells(w.new_cells);
    };
    for (const CoverageWindow& closed : projection.closed) add(closed);
    const int64_t start = projection.window * window;
    if (timesteps > start) {
      add({.start_step = start,
           .end_step = std::min(timesteps, start + window),
           .visited = CountBits(projection.window_seen),
           .new_cells = projection.window_new});
    }
  }
}

}  // namespace dcs::run
