// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_STAGED_SCHEDULE_H_
#define DCS_ENV_STAGED_SCHEDULE_H_

// Multi-stage schedules (the paper's §multi-stage; docs/reference.md, "Multi-stage schedules"):
// training is split into stages of fixed lengths in environment steps of the run, each with its own
// schedule (a one-stage schedule is the ordinary single-schedule case; `constant` is Identity).
//
// When a stage change takes effect: an episode runs the stage in force when it started, the
// stage whose span of the run's global environment steps contains the step count at its
// reset. A boundary passed mid-episode therefore takes effect at that environment's next
// reset: no episode mixes two schedules, and no episode is cut short. Past the last stage's
// end, the last stage stays in force. The policy, optimiser and step counters are untouched.
// The new stage's generators derive from its own seed and the slot's running episode count.
//
// Confined to one thread; one instance per environment slot and feature.

#include <cstdint>
#include <memory>
#include <vector>

#include "absl/status/statusor.h"
#include "env/schedule.h"

namespace dcs::env {

struct ScheduleStage {
  int64_t steps = 0;  // length in environment steps of the run; > 0
  ScheduleSpec spec;
};

class StagedSchedule {
 public:
  // INVALID_ARGUMENT if `stages` is empty or a length is not positive.
  static absl::StatusOr<StagedSchedule> Create(std::vector<ScheduleStage> stages);

  // The index of the stage in force for an episode that starts at `global_step`.
  int StageAt(int64_t global_step) const;

  // Starts an episode at `global_step` (switching stage if a boundary has passed); returns the
  // value to apply, as Schedule::Reset.
  double Reset(double initial, EpisodeId id, int64_t global_step);

  // As Schedule::Next, with the current stage's schedule.
  double Next(int64_t k, double current) { return schedule_->Next(k, current); }

  int stage() const { return stage_; }
  const std::vector<ScheduleStage>& stages() const { return stages_; }

 private:
  explicit StagedSchedule(std::vector<ScheduleStage> stages) : stages_(std::move(stages)) {}

  std::vector<ScheduleStage> stages_;
  int stage_ = -1;  // none built yet
  std::unique_ptr<Schedule> schedule_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_STAGED_SCHEDULE_H_
