// Copyright 2026 The DCS Authors.
#include "env/car_racing_centerline.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dcs::env {
namespace {

constexpr double kRearAxleY = -82 * kCarSize;  // hull-local y of the rear wheels
constexpr double kWheelBase = (80 + 82) * kCarSize;

// The index of the track point nearest to (x, y) among those from `first` to `last` (wrapping).
int Nearest(const std::vector<TrackPoint>& points, double x, double y, int first, int last) {
  const int n = static_cast<int>(points.size());
  int best = first;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int k = first; k <= last; ++k) {
    const int i = ((k % n) + n) % n;
    const double dx = points[i].x - x;
    const double dy = points[i].y - y;
    const double d2 = dx * dx + dy * dy;
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
    }
  }
  return best;
}

}  // namespace

CenterlineDriver::CenterlineDriver(const CenterlineDriverOptions& options) : options_(options) {}

void CenterlineDriver::Reset(const CarRacing& env) {
  const std::vector<TrackPoint>& points = env.track().points;
  const int n = static_cast<int>(points.size());
  const int w = options_.curvature_window;

  // Curvature from the change of the road direction over a window, then the speed it allows.
  target_speed_.assign(n, options_.max_speed);
  for (int i = 0; i < n; ++i) {
    const double b0 = points[((i - w) % n + n) % n].beta;
    const double b1 = points[(i + w) % n].beta;
    double turn = b1 - b0;
    // beta is continuous along the loop except where the loop closes (a jump of 2 pi k).
    turn = std::remainder(turn, 2 * 3.141592653589793);
    const double curvature = std::abs(turn) / (2 * w * kTrackDetailStep);
    if (curvature > 1e-9) {
      target_speed_[i] = std::clamp(std::sqrt(options_.lateral_accel / curvature),
                                    options_.min_speed, options_.max_speed);
    }
  }
  // Brake in time: v[i]^2 <= v[i + 1]^2 + 2 a ds, propagated backwards around the loop twice.
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = n - 1; i >= 0; --i) {
      const double next = target_speed_[(i + 1) % n];
      const double reachable = std::sqrt(next * next + 2 * options_.brake_decel * kTrackDetailStep);
      target_speed_[i] = std::min(target_speed_[i], reachable);
    }
  }

  const b2Vec2 p = env.car().hull()->GetPosition();
  nearest_ = Nearest(points, p.x, p.y, 0, n - 1);
}

void CenterlineDriver::Act(const CarRacing& env, std::span<float, CarRacing::kActionSize> action) {
  const std::vector<TrackPoint>& points = env.track().points;
  const int n = static_cast<int>(points.size());
  const b2Body& hull = *env.car().hull();
  const b2Vec2 rear = hull.GetWorldPoint(b2Vec2(0, static_cast<float>(kRearAxleY)));
  const b2Vec2 velocity = hull.GetLinearVelocity();
  const double speed = std::hypot(velocity.x, velocity.y);

  // Track the nearest point locally (the car moves at most a few points per step).
  nearest_ = Nearest(points, rear.x, rear.y, nearest_ - 5, nearest_ + 25);

  // Pure pursuit toward the point one look-ahead distance further along the centre line.
  const double lookahead = std::clamp(options_.min_lookahead + options_.lookahead_time * speed,
                                      options_.min_lookahead, options_.max_lookahead);
  const int ahead = static_cast<int>(std::lround(lookahead / kTrackDetailStep));
  const TrackPoint& target = points[(nearest_ + ahead) % n];
  const b2Vec2 local = hull.GetLocalVector(
      b2Vec2(static_cast<float>(target.x - rear.x), static_cast<float>(target.y - rear.y)));
  const double d2 = std::max(
      static_cast<double>(local.x) * local.x + static_cast<double>(local.y) * local.y, 1e-6);
  const double curvature = 2 * local.x / d2;  // positive: the target is to the right
  double steer = std::atan(curvature * kWheelBase);
  // Yaw-rate damping: the yaw rate of the pursuit curve is -curvature * speed (a right turn
  // is clockwise); push back against any excess.
  const double yaw_error = hull.GetAngularVelocity() - (-curvature * speed);
  steer += options_.yaw_damping * yaw_error;
  action[0] = static_cast<float>(std::clamp(steer, -1.0, 1.0));

  // Speed: the profile a little ahead of the car (the car needs a few steps to react).
  const int preview = static_cast<int>(std::lround(speed * 0.1 / kTrackDetailStep)) + 1;
  const double target_speed = target_speed_[(nearest_ + preview) % n];
  double gas = 0;
  double brake = 0;
  if (speed < target_speed) {
    gas = std::clamp((target_speed - speed) * options_.gas_gain, 0.0, 1.0);
  } else if (speed > target_speed + options_.speed_margin) {
    brake = std::clamp((speed - target_speed) * options_.brake_gain, 0.0, 0.8);
  }
  action[1] = static_cast<float>(gas);
  action[2] = static_cast<float>(brake);
}

}  // namespace dcs::env
