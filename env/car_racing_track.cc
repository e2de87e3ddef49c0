// Copyright 2026 The DCS Authors.
#include "env/car_racing_track.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dcs::env {
namespace {

constexpr double kPi = std::numbers::pi;

struct Checkpoint {
  double alpha;
  double x;
  double y;
};

double Sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

// Python's negative indexing: track[i] for i in [-n, n).
template <typename T>
const T& At(std::span<const T> v, int i) {
  const int n = static_cast<int>(v.size());
  return v[i < 0 ? i + n : i];
}

}  // namespace

std::optional<std::vector<TrackPoint>> TryTraceTrack(Random& random) {
  // Checkpoints: two draws each, also where they are overwritten (c == 0 and c == 11).
  std::array<Checkpoint, kNumCheckpoints> checkpoints;
  double start_alpha = 0;
  for (int c = 0; c < kNumCheckpoints; ++c) {
    const double noise = random.Uniform(0, 2 * kPi * 1 / kNumCheckpoints);
    double alpha = 2 * kPi * c / kNumCheckpoints + noise;
    double rad = random.Uniform(kTrackRad / 3, kTrackRad);
    if (c == 0) {
      alpha = 0;
      rad = 1.5 * kTrackRad;
    }
    if (c == kNumCheckpoints - 1) {
      alpha = 2 * kPi * c / kNumCheckpoints;
      start_alpha = 2 * kPi * (-0.5) / kNumCheckpoints;
      rad = 1.5 * kTrackRad;
    }
    checkpoints[c] = {alpha, rad * std::cos(alpha), rad * std::sin(alpha)};
  }

  // Trace from checkpoint to checkpoint.
  double x = 1.5 * kTrackRad;
  double y = 0;
  double beta = 0;
  int dest_i = 0;
  int laps = 0;
  int no_freeze = 2500;
  bool visited_other_side = false;
  std::vector<TrackPoint> track;
  track.reserve(2500);
  while (true) {
    double alpha = std::atan2(y, x);
    if (visited_other_side && alpha > 0) {
      ++laps;
      visited_other_side = false;
    }
    if (alpha < 0) {
      visited_other_side = true;
      alpha += 2 * kPi;
    }

    double dest_x = 0;
    double dest_y = 0;
    while (true) {  // find the destination checkpoint
      bool failed = true;
      while (true) {
        const Checkpoint& dest = checkpoints[dest_i % kNumCheckpoints];
        dest_x = dest.x;
        dest_y = dest.y;
        if (alpha <= dest.alpha) {
          failed = false;
          break;
        }
        ++dest_i;
        if (dest_i % kNumCheckpoints == 0) break;
      }
      if (!failed) break;
      alpha -= 2 * kPi;
    }

    const double r1x = std::cos(beta);
    const double r1y = std::sin(beta);
    const double p1x = -r1y;
    const double p1y = r1x;
    const double dest_dx = dest_x - x;
    const double dest_dy = dest_y - y;
    double proj = r1x * dest_dx + r1y * dest_dy;
    while (beta - alpha > 1.5 * kPi) beta -= 2 * kPi;
    while (beta - alpha < -1.5 * kPi) beta += 2 * kPi;
    const double prev_beta = beta;
    proj *= kCarRacingScale;
    if (proj > 0.3) beta -= std::min(kTrackTurnRate, std::abs(0.001 * proj));
    if (proj < -0.3) beta += std::min(kTrackTurnRate, std::abs(0.001 * proj));
    x += p1x * kTrackDetailStep;
    y += p1y * kTrackDetailStep;
    track.push_back({alpha, prev_beta * 0.5 + beta * 0.5, x, y});
    if (laps > 4) break;
    if (--no_freeze == 0) break;
  }

  // The closed loop: between the last two passes through start_alpha.
  int i1 = -1;
  int i2 = -1;
  int i = static_cast<int>(track.size());
  while (true) {
    --i;
    if (i == 0) return std::nullopt;
    const bool pass_through_start =
        track[i].alpha > start_alpha && track[i - 1].alpha <= start_alpha;
    if (pass_through_start && i2 == -1) {
      i2 = i;
    } else if (pass_through_start && i1 == -1) {
      i1 = i;
      break;
    }
  }
  if (i2 - 1 <= i1) return std::nullopt;  // an empty slice (Gymnasium would raise)
  std::vector<TrackPoint> loop(track.begin() + i1, track.begin() + (i2 - 1));

  // Glue check, component-wise as Gymnasium writes it.
  const double first_beta = loop.front().beta;
  const double first_perp_x = std::cos(first_beta);
  const double first_perp_y = std::sin(first_beta);
  const double gx = first_perp_x * (loop.front().x - loop.back().x);
  const double gy = first_perp_y * (loop.front().y - loop.back().y);
  const double well_glued_together = std::sqrt(gx * gx + gy * gy);
  if (well_glued_together > kTrackDetailStep) return std::nullopt;
  return loop;
}

std::vector<bool> ComputeBorders(std::span<const TrackPoint> points) {
  const int n = static_cast<int>(points.size());
  std::vector<bool> border(n, false);
  for (int i = 0; i < n; ++i) {
    bool good = true;
    double oneside = 0;
    for (int neg = 0; neg < kBorderMinCount; ++neg) {
      const double beta1 = At(points, i - neg - 0).beta;
      const double beta2 = At(points, i - neg - 1).beta;
      good = good && std::abs(beta1 - beta2) > kTrackTurnRate * 0.2;
      oneside += Sign(beta1 - beta2);
    }
    good = good && std::abs(oneside) == kBorderMinCount;
    border[i] = good;
  }
  // Spread backwards, in place: a negative index wraps to the end and is overwritten again
  // when the loop reaches it.
  for (int i = 0; i < n; ++i) {
    for (int neg = 0; neg < kBorderMinCount; ++neg) {
      const int j = i - neg < 0 ? i - neg + n : i - neg;
      border[j] = border[j] || border[i];
    }
  }
  return border;
}

Track GenerateTrack(Random& random) {
  Track track;
  while (true) {
    ++track.attempts;
    std::optional<std::vector<TrackPoint>> points = TryTraceTrack(random);
    if (points.has_value()) {
      track.points = *std::move(points);
      break;
    }
  }
  track.border = ComputeBorders(track.points);
  return track;
}

std::vector<RoadPolygon> BuildRoadPolygons(const Track& track, Rgb road_color) {
  const std::span<const TrackPoint> points = track.points;
  const int n = track.size();
  std::vector<RoadPolygon> polygons;
  polygons.reserve(2 * n);
  const double w = kTrackWidth;
  for (int i = 0; i < n; ++i) {
    const TrackPoint& p1 = points[i];
    const TrackPoint& p2 = At(points, i - 1);
    const double c1 = std::cos(p1.beta);
    const double s1 = std::sin(p1.beta);
    const double c2 = std::cos(p2.beta);
    const double s2 = std::sin(p2.beta);
    const WorldPoint road1_l = {p1.x - w * c1, p1.y - w * s1};
    const WorldPoint road1_r = {p1.x + w * c1, p1.y + w * s1};
    const WorldPoint road2_l = {p2.x - w * c2, p2.y - w * s2};
    const WorldPoint road2_r = {p2.x + w * c2, p2.y + w * s2};
    polygons.push_back({{road1_l, road1_r, road2_r, road2_l}, i, road_color});
    if (track.border[i]) {
      const double side = Sign(p2.beta - p1.beta);
      const WorldPoint b1_l = {p1.x + side * w * c1, p1.y + side * w * s1};
      const WorldPoint b1_r = {p1.x + side * (w + kTrackBorder) * c1,
                               p1.y + side * (w + kTrackBorder) * s1};
      const WorldPoint b2_l = {p2.x + side * w * c2, p2.y + side * w * s2};
      const WorldPoint b2_r = {p2.x + side * (w + kTrackBorder) * c2,
                               p2.y + side * (w + kTrackBorder) * s2};
      const Rgb kerb = i % 2 == 0 ? Rgb{255, 255, 255} : Rgb{255, 0, 0};
      polygons.push_back({{b1_l, b1_r, b2_r, b2_l}, -1, kerb});
    }
  }
  return polygons;
}

}  // namespace dcs::env
