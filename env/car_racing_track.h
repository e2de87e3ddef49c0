// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CAR_RACING_TRACK_H_
#define DCS_ENV_CAR_RACING_TRACK_H_

// CarRacing-v3's track generator (Gymnasium car_racing.py L307-495), pure:
// random checkpoints, the traced centre line, the closed-loop extraction and glue check, the
// red/white kerb flags, and the road and kerb quads in Gymnasium's draw order. Every draw and
// every floating-point expression follows Gymnasium's order, so a Random seeded as Gymnasium
// seeds its environment gives Gymnasium's track. No Box2D here. Thread-safe (free functions).

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "common/random.h"
#include "env/raster.h"

namespace dcs::env {

// Constants of car_racing.py (world units; SCALE = 6 pixels of the 1000x800 canvas per unit at
// zoom 1).
inline constexpr double kCarRacingScale = 6.0;
inline constexpr double kTrackRad = 900 / kCarRacingScale;        // 150
inline constexpr double kPlayfield = 2000 / kCarRacingScale;      // 333.33
inline constexpr double kTrackDetailStep = 21 / kCarRacingScale;  // 3.5
inline constexpr double kTrackTurnRate = 0.31;
inline constexpr double kTrackWidth = 40 / kCarRacingScale;  // half-width of the road
inline constexpr double kTrackBorder = 8 / kCarRacingScale;  // kerb width
inline constexpr int kBorderMinCount = 4;
inline constexpr int kNumCheckpoints = 12;
inline constexpr int kTrackUniformsPerAttempt = 2 * kNumCheckpoints;  // 24

struct WorldPoint {
  double x = 0;
  double y = 0;
};

// One traced centre-line point: the polar angle of the point seen from the origin (as used by
// the generator, possibly shifted by -2 pi), the road direction angle beta (the road runs along
// (-sin beta, cos beta); consecutive betas differ by at most 0.31 rad modulo 2 pi, but beta
// itself jumps by 2 pi where the generator re-wrapped it) and the position.
struct TrackPoint {
  double alpha = 0;
  double beta = 0;
  double x = 0;
  double y = 0;
};

// A road or kerb quad in world units, with its render colour. Tile quads have tile >= 0 (their
// colour changes when touched, see CarRacing); kerbs have tile == -1.
struct RoadPolygon {
  std::array<WorldPoint, 4> points;
  int tile = -1;
  Rgb color;
};

struct Track {
  std::vector<TrackPoint> points;  // N points; tile i spans points[i - 1] .. points[i]
  std::vector<bool> border;        // kerb on tile i
  int attempts = 0;                // generator calls it took (each draws 24 uniforms)

  int size() const { return static_cast<int>(points.size()); }
};

// One call of Gymnasium's _create_track up to the glue check: draws exactly
// kTrackUniformsPerAttempt uniforms (two per checkpoint, also for the two overwritten ones) and
// returns the closed loop, or nullopt when the loop could not be extracted or its ends are more
// than kTrackDetailStep apart (Gymnasium then calls it again).
std::optional<std::vector<TrackPoint>> TryTraceTrack(Random& random);

// Gymnasium's reset loop: TryTraceTrack until it succeeds, then the kerb flags. Never gives up
// (neither does Gymnasium; in practice a few percent of attempts fail).
Track GenerateTrack(Random& random);

// The kerb flags: a tile gets a kerb when it ends a run of kBorderMinCount consecutive turns in
// one direction, each sharper than 0.2 * kTrackTurnRate, and the flag is then spread to the
// kBorderMinCount - 1 tiles before it, in place and in Gymnasium's order (indices wrap).
std::vector<bool> ComputeBorders(std::span<const TrackPoint> points);

// Road quads in Gymnasium's road_poly order: tile i's quad [road1_l, road1_r, road2_r, road2_l]
// then, if it has one, its kerb quad (white for even i, red for odd i). Tile quads get
// `road_color` here; CarRacing replaces it with the tile's current colour when drawing.
std::vector<RoadPolygon> BuildRoadPolygons(const Track& track, Rgb road_color);

}  // namespace dcs::env

#endif  // DCS_ENV_CAR_RACING_TRACK_H_
