// Copyright 2026 The DCS Authors.
#include "env/staged_schedule.h"

#include "absl/strings/str_cat.h"

namespace dcs::env {

absl::StatusOr<StagedSchedule> StagedSchedule::Create(std::vector<ScheduleStage> stages) {
  if (stages.empty()) return absl::InvalidArgumentError("a schedule needs at least one stage");
  for (size_t i = 0; i < stages.size(); ++i) {
    if (stages[i].steps <= 0) {
      return absl::InvalidArgumentError(absl::StrCat("stage ", i + 1, " must last a positive ",
                                                     "number of steps, got ", stages[i].steps));
    }
  }
  return StagedSchedule(std::move(stages));
}

int StagedSchedule::StageAt(int64_t global_step) const {
  int64_t end = 0;
  for (size_t i = 0; i < stages_.size(); ++i) {
    end += stages_[i].steps;
    if (global_step < end) return static_cast<int>(i);
  }
  return static_cast<int>(stages_.size()) - 1;
}

double StagedSchedule::Reset(double initial, EpisodeId id, int64_t global_step) {
  const int stage = StageAt(global_step);
  if (stage != stage_) {
    stage_ = stage;
    schedule_ = MakeSchedule(stages_[stage].spec);
  }
  return schedule_->Reset(initial, id);
}

}  // namespace dcs::env
