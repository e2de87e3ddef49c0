// Copyright 2026 The DCS Authors.
//
// The families that hold the value and change it at random times: Sudden Jump (the paper's
// Stochastic Jumps) and Piecewise Constant (docs/reference.md, "Schedule families").

#include "env/schedule_internal.h"

namespace dcs::env::internal {
namespace {

class SuddenJump final : public BoundedSchedule {
 public:
  SuddenJump(const ScheduleSpec& spec, const SuddenJumpParams& params)
      : BoundedSchedule(spec), params_(params) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    next_jump_ = DrawInterval(params_.interval);
    return Clip(initial);
  }

  double Next(int64_t k, double current) override {
    double value = current;
    while (k >= next_jump_) {
      const double magnitude = random_.Uniform(params_.step_size.lo, params_.step_size.hi);
      value += DirectionSign(params_.direction, params_.direction_prob) * magnitude;
      if (params_.edge_mode == EdgeMode::kReflect) value = Reflect(value);
      next_jump_ += DrawInterval(params_.interval);
    }
    return Clip(value);
  }

 private:
  const SuddenJumpParams params_;
  int64_t next_jump_ = 0;
};

class PiecewiseConstant final : public BoundedSchedule {
 public:
  PiecewiseConstant(const ScheduleSpec& spec, const PiecewiseConstantParams& params)
      : BoundedSchedule(spec), params_(params) {}

  // The episode keeps its pool-drawn value until the first switch.
  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    next_switch_ = DrawInterval(params_.interval);
    return Clip(initial);
  }

  double Next(int64_t k, double current) override {
    double value = current;
    if (k >= next_switch_) {  // at most one switch per call
      value = params_.values[random_.Integers(0, static_cast<int64_t>(params_.values.size()))];
      next_switch_ += DrawInterval(params_.interval);
    }
    return Clip(value);
  }

 private:
  const PiecewiseConstantParams params_;
  int64_t next_switch_ = 0;
};

}  // namespace

std::unique_ptr<Schedule> MakeSuddenJump(const ScheduleSpec& spec,
                                         const SuddenJumpParams& params) {
  return std::make_unique<SuddenJump>(spec, params);
}

std::unique_ptr<Schedule> MakePiecewiseConstant(const ScheduleSpec& spec,
                                                const PiecewiseConstantParams& params) {
  return std::make_unique<PiecewiseConstant>(spec, params);
}

}  // namespace dcs::env::internal
