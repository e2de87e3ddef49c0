// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CAR_RACING_CENTERLINE_H_
#define DCS_ENV_CAR_RACING_CENTERLINE_H_

// A scripted CarRacing driver that follows the track's centre line, the "does the port drive"
// baseline (as Gymnasium's heuristic is for BipedalWalker). It reads the track and the car's
// pose from the environment's read-only accessors, not from the picture:
//   - steering: pure pursuit from the rear axle toward a look-ahead point on the centre line
//     (look-ahead distance growing with speed), with a little yaw-rate damping;
//   - speed: a target-speed profile computed once per track from the centre line's curvature
//     (lateral-acceleration limit) and propagated backwards with a braking-deceleration limit,
//     so the driver brakes before sharp turns; gas below the target, brake above it.
// Deterministic: the same environment state gives the same action. Confined to one thread.

#include <span>
#include <vector>

#include "env/car_racing.h"

namespace dcs::env {

struct CenterlineDriverOptions {
  double min_lookahead = 7.0;    // m, look-ahead distance at rest
  double lookahead_time = 0.22;  // s, added look-ahead per unit of speed
  double max_lookahead = 22.0;   // m
  double max_speed = 110.0;      // m/s on straights
  double min_speed = 18.0;       // m/s in the sharpest turns
  double lateral_accel = 100.0;  // m/s^2 allowed in turns (spins out from ~130)
  double brake_decel = 70.0;     // m/s^2 assumed when braking for a turn
  int curvature_window = 5;      // track points each side over which curvature is measured
  double gas_gain = 0.1;         // gas per m/s below the target
  double brake_gain = 0.08;      // brake per m/s above the target
  double speed_margin = 2.0;     // m/s above the target tolerated before braking
  double yaw_damping = 0.06;     // steer per rad/s of yaw rate away from the pursuit curve
};

class CenterlineDriver {
 public:
  explicit CenterlineDriver(const CenterlineDriverOptions& options = {});

  // Reads the new track; call after every env.Reset.
  void Reset(const CarRacing& env);

  // Writes [steer, gas, brake] for the current state of `env`.
  void Act(const CarRacing& env, std::span<float, CarRacing::kActionSize> action);

  // The target speed at track point i (m/s), for tests.
  double target_speed(int i) const { return target_speed_[i]; }
  // The track point nearest to the car at the last Act (or Reset).
  int nearest_point() const { return nearest_; }

 private:
  CenterlineDriverOptions options_;
  std::vector<double> target_speed_;  // per track point
  int nearest_ = 0;
};

}  // namespace dcs::env

#endif  // DCS_ENV_CAR_RACING_CENTERLINE_H_
