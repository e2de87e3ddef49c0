// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_WORKER_REPORTS_H_
#define DCS_RUN_WORKER_REPORTS_H_

// What workers report of a run to the coordinator: its learner's progress after each update,
// and an actor's returns in one of its evaluation contexts. Plain data.

#include <cstdint>
#include <optional>
#include <vector>

namespace dcs::run {

// What a run's learner reports after each update.
struct RunProgress {
  int64_t timesteps = 0;
  int64_t policy_version = 0;
  double steps_per_second = 0;
  double recent_return = 0;                // NaN before the first episode
  std::optional<double> avg_combined;      // of the latest evaluation
  std::optional<int64_t> evaluation_step;  // its step
};

// One context's episodes as an actor evaluated them.
struct ContextReturns {
  std::vector<double> returns;  // one per episode, in episode order
  double seconds = 0;
};

}  // namespace dcs::run

#endif  // DCS_RUN_WORKER_REPORTS_H_
