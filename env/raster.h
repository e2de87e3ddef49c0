// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_RASTER_H_
#define DCS_ENV_RASTER_H_

// A small software rasteriser for environment images (CarRacing's 96x96 observation, frames
// of `dcs env render`): filled polygons and lines on an RGB canvas, and an area-averaging
// downscale. No anti-aliasing: a pixel is covered when its centre is inside the polygon (the
// spec allows this for images that must look like Gymnasium's rather than equal them
// bit for bit). Coordinates are in pixels, x to the right and y down, (0, 0) the top-left
// corner of the top-left pixel. Thread-compatible.

#include <cstdint>
#include <span>
#include <vector>

namespace dcs::env {

struct Rgb {
  uint8_t r = 0;
  uint8_t g = 0;
  uint8_t b = 0;
};

struct PixelPoint {
  double x = 0;
  double y = 0;
};

class Canvas {
 public:
  // REQUIRES: width, height > 0.
  Canvas(int width, int height) : width_(width), height_(height), pixels_(3 * width * height) {}

  int width() const { return width_; }
  int height() const { return height_; }
  // Row-major RGB, 3 bytes per pixel.
  std::span<const uint8_t> pixels() const { return pixels_; }
  std::span<uint8_t> pixels() { return pixels_; }

  void Clear(Rgb color);

  // Fills every pixel whose centre lies inside the polygon (even-odd rule, so any simple
  // polygon, convex or not). Clipped to the canvas. REQUIRES: at most 32 vertices.
  void FillPolygon(std::span<const PixelPoint> vertices, Rgb color);

  // Fills the axis-aligned rectangle [x0, x1) x [y0, y1) of pixel centres (corners in any
  // order), clipped.
  void FillRect(double x0, double y0, double x1, double y1, Rgb color);

  // A 1-pixel line from a to b (DDA over pixel centres), clipped.
  void DrawLine(PixelPoint a, PixelPoint b, Rgb color);

  // Writes this canvas shrunk to `out_width` x `out_height` into `out` (RGB, row-major), each
  // output pixel the area-weighted mean of the source pixels under it, rounded down.
  // REQUIRES: out.size() == 3 * out_width * out_height; the output is no larger than the canvas.
  void Downscale(int out_width, int out_height, std::span<uint8_t> out) const;

 private:
  void FillSpan(int y, int x0, int x1, Rgb color);

  int width_;
  int height_;
  std::vector<uint8_t> pixels_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_RASTER_H_
