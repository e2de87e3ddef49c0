// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CAR_RACING_RENDER_H_
#define DCS_ENV_CAR_RACING_RENDER_H_

// CarRacing-v3's picture (CarRacing.render): Gymnasium's 1000x800 top-down view centred on the
// car (background, grass patches, road tiles and kerbs, wheels with stripes, hull, payload),
// flipped so the car points up, with the indicator bar and the score along the bottom; and the
// 96x96 observation made from it.
//
// Rather than drawing 1000x800 pixels and shrinking them, everything is drawn straight into a
// smaller canvas with the same camera scaled per axis (polygon vertices are still truncated to
// integers in 1000x800 coordinates first, as pygame does), and the observation is a
// supersampled (k*96)x(k*96) canvas box-filtered down to 96x96. Polygons are filled by pixel
// centre, without anti-aliasing; outside the view they are culled. The score is drawn with a
// 5x7 block font in place of pygame's FreeSansBold (a ~9x5-pixel smudge in the observation).
// Thread-compatible.

#include <cstdint>
#include <span>

#include "env/car_dynamics.h"
#include "env/car_racing_track.h"
#include "env/raster.h"

namespace dcs::env {

struct CarRacingColors {
  Rgb background = {102, 204, 102};
  Rgb grass = {102, 230, 102};
  Rgb road = {102, 102, 102};
};

// Everything one frame shows. Borrowed for the duration of the draw call.
struct CarRacingFrame {
  const Car* car = nullptr;
  std::span<const RoadPolygon> road;  // in draw order
  std::span<const Rgb> tile_colors;   // current colour of tile i (used for tile polygons)
  CarRacingColors colors;
  double time = 0;   // simulated seconds including the reset step (the zoom animates in 1 s)
  double score = 0;  // Gymnasium's self.reward, shown as "%04.0f"
};

// Draws the 1000x800 view scaled to `canvas` (x by width/1000, y by height/800), after the
// vertical flip, with the indicator bar and the score. Overwrites every pixel.
void DrawCarRacingFrame(const CarRacingFrame& frame, Canvas& canvas);

// The 96x96x3 observation (row 0 at the top, RGB), drawn at `supersample` times the resolution
// per axis and box-filtered (each output pixel the mean of its k x k block, rounded down).
class CarRacingObservationRenderer {
 public:
  static constexpr int kSize = 96;

  // REQUIRES: 1 <= supersample <= 8.
  explicit CarRacingObservationRenderer(int supersample = 2);

  int supersample() const { return supersample_; }
  // The supersampled canvas of the last Render.
  const Canvas& canvas() const { return canvas_; }

  void Render(const CarRacingFrame& frame, std::span<uint8_t, kSize * kSize * 3> observation);

 private:
  int supersample_;
  Canvas canvas_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_CAR_RACING_RENDER_H_
