// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_STEP_RESULT_H_
#define DCS_ENV_STEP_RESULT_H_

// What one environment step returns besides the observation. Termination (the task ended:
// the pole fell) is kept apart from truncation (the time limit cut the episode), because the
// learner bootstraps the value of a truncated episode and not of a terminated one.

namespace dcs::env {

struct StepResult {
  double reward = 0;
  bool terminated = false;
  bool truncated = false;

  bool done() const { return terminated || truncated; }
};

}  // namespace dcs::env

#endif  // DCS_ENV_STEP_RESULT_H_
