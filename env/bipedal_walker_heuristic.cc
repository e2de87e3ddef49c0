// Copyright 2026 The DCS Authors.
#include "env/bipedal_walker_heuristic.h"

#include <algorithm>
#include <optional>

namespace dcs::env {
namespace {

constexpr double kSpeed = 0.29;  // falls forward at higher speeds
constexpr double kSupportKneeAngle = 0.1;

}  // namespace

void WalkerHeuristic::Reset() { *this = WalkerHeuristic(); }

std::array<float, 4> WalkerHeuristic::Act(std::span<const float, 24> observation) {
  // Observation values as Python sees them: float32 widened to double.
  auto s = [&observation](int i) { return static_cast<double>(observation[i]); };
  const int moving_base = 4 + 5 * moving_leg_;
  const int supporting_base = 4 + 5 * supporting_leg_;
  std::array<std::optional<double>, 2> hip_target;   // -0.8 .. +1.1
  std::array<std::optional<double>, 2> knee_target;  // -0.6 .. +0.9 (knee angle + 1)
  std::array<double, 2> hip_todo = {0.0, 0.0};
  std::array<double, 2> knee_todo = {0.0, 0.0};

  if (phase_ == kStayOnOneLeg) {
    hip_target[moving_leg_] = 1.1;
    knee_target[moving_leg_] = -0.6;
    supporting_knee_angle_ += 0.03;
    if (s(2) > kSpeed) supporting_knee_angle_ += 0.03;
    supporting_knee_angle_ = std::min(supporting_knee_angle_, kSupportKneeAngle);
    knee_target[supporting_leg_] = supporting_knee_angle_;
    if (s(supporting_base) < 0.10) phase_ = kPutOtherDown;  // supporting leg is behind
  }
  if (phase_ == kPutOtherDown) {
    hip_target[moving_leg_] = 0.1;
    knee_target[moving_leg_] = kSupportKneeAngle;
    knee_target[supporting_leg_] = supporting_knee_angle_;
    if (s(moving_base + 4) != 0) {
      phase_ = kPushOff;
      supporting_knee_angle_ = std::min(s(moving_base + 2), kSupportKneeAngle);
    }
  }
  if (phase_ == kPushOff) {
    knee_target[moving_leg_] = supporting_knee_angle_;
    knee_target[supporting_leg_] = 1.0;
    if (s(supporting_base + 2) > 0.88 || s(2) > 1.2 * kSpeed) {
      phase_ = kStayOnOneLeg;
      moving_leg_ = 1 - moving_leg_;
      supporting_leg_ = 1 - moving_leg_;
    }
  }

  // Python's `if target:` skips an unset target and one that is exactly 0.0.
  auto set = [](const std::optional<double>& target) { return target.has_value() && *target != 0; };
  if (set(hip_target[0])) hip_todo[0] = 0.9 * (*hip_target[0] - s(4)) - 0.25 * s(5);
  if (set(hip_target[1])) hip_todo[1] = 0.9 * (*hip_target[1] - s(9)) - 0.25 * s(10);
  if (set(knee_target[0])) knee_todo[0] = 4.0 * (*knee_target[0] - s(6)) - 0.25 * s(7);
  if (set(knee_target[1])) knee_todo[1] = 4.0 * (*knee_target[1] - s(11)) - 0.25 * s(12);

  for (int k = 0; k < 2; ++k) {
    hip_todo[k] -= 0.9 * (0 - s(0)) - 1.5 * s(1);  // keep the head straight
    knee_todo[k] -= 15.0 * s(3);                   // damp vertical oscillations
  }
  const std::array<double, 4> a = {hip_todo[0], knee_todo[0], hip_todo[1], knee_todo[1]};
  std::array<float, 4> action;
  for (int j = 0; j < 4; ++j) action[j] = static_cast<float>(std::clamp(0.5 * a[j], -1.0, 1.0));
  return action;
}

}  // namespace dcs::env
