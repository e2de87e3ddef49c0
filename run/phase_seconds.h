// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_PHASE_SECONDS_H_
#define DCS_RUN_PHASE_SECONDS_H_

// Where a run's wall time went, in seconds, in the process that trained it (`dcs train`:
// learner/training_run.h), for its summary. Plain data.

namespace dcs::run {

struct PhaseSeconds {
  double rollouts = 0;     // stepping the environments and acting
  double updates = 0;      // learning from the rollouts
  double evaluations = 0;  // the evaluations that fell due
  double checkpoints = 0;  // writing checkpoints and the evaluation log
};

}  // namespace dcs::run

#endif  // DCS_RUN_PHASE_SECONDS_H_
