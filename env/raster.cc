// Copyright 2026 The DCS Authors.
#include "env/raster.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace dcs::env {

void Canvas::Clear(Rgb color) {
  for (size_t i = 0; i < pixels_.size(); i += 3) {
    pixels_[i] = color.r;
    pixels_[i + 1] = color.g;
    pixels_[i + 2] = color.b;
  }
}

void Canvas::FillSpan(int y, int x0, int x1, Rgb color) {
  x0 = std::max(x0, 0);
  x1 = std::min(x1, width_);
  uint8_t* p = pixels_.data() + 3 * (static_cast<size_t>(y) * width_ + x0);
  for (int x = x0; x < x1; ++x, p += 3) {
    p[0] = color.r;
    p[1] = color.g;
    p[2] = color.b;
  }
}

void Canvas::FillPolygon(std::span<const PixelPoint> vertices, Rgb color) {
  const size_t n = vertices.size();
  assert(n <= 32);
  if (n < 3) return;
  double min_y = vertices[0].y;
  double max_y = vertices[0].y;
  for (const PixelPoint& v : vertices) {
    min_y = std::min(min_y, v.y);
    max_y = std::max(max_y, v.y);
  }
  // Rows whose centre y + 0.5 lies in [min_y, max_y).
  const int row_begin = std::max(0, static_cast<int>(std::ceil(min_y - 0.5)));
  const int row_end = std::min(height_, static_cast<int>(std::ceil(max_y - 0.5)));
  std::array<double, 32> crossings;
  for (int y = row_begin; y < row_end; ++y) {
    const double yc = y + 0.5;
    size_t count = 0;
    for (size_t i = 0, j = n - 1; i < n; j = i++) {
      const PixelPoint& a = vertices[j];
      const PixelPoint& b = vertices[i];
      // Half-open in y, so a vertex on the scanline counts once.
      if ((a.y <= yc && yc < b.y) || (b.y <= yc && yc < a.y)) {
        crossings[count++] = a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y);
      }
    }
    std::sort(crossings.begin(), crossings.begin() + count);
    for (size_t k = 0; k + 1 < count; k += 2) {
      // Pixels whose centre x + 0.5 lies in [crossings[k], crossings[k + 1]).
      FillSpan(y, static_cast<int>(std::ceil(crossings[k] - 0.5)),
               static_cast<int>(std::ceil(crossings[k + 1] - 0.5)), color);
    }
  }
}

void Canvas::FillRect(double x0, double y0, double x1, double y1, Rgb color) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  const int row_begin = std::max(0, static_cast<int>(std::ceil(y0 - 0.5)));
  const int row_end = std::min(height_, static_cast<int>(std::ceil(y1 - 0.5)));
  const int col_begin = static_cast<int>(std::ceil(x0 - 0.5));
  const int col_end = static_cast<int>(std::ceil(x1 - 0.5));
  for (int y = row_begin; y < row_end; ++y) FillSpan(y, col_begin, col_end, color);
}

void Canvas::DrawLine(PixelPoint a, PixelPoint b, Rgb color) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy))));
  for (int i = 0; i <= steps; ++i) {
    const double t = steps == 0 ? 0.0 : static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::floor(a.x + t * dx));
    const int y = static_cast<int>(std::floor(a.y + t * dy));
    if (x >= 0 && x < width_ && y >= 0 && y < height_) FillSpan(y, x, x + 1, color);
  }
}

void Canvas::Downscale(int out_width, int out_height, std::span<uint8_t> out) const {
  assert(out.size() == static_cast<size_t>(3 * out_width * out_height));
  // Separable area averaging: X pass into floats, then Y pass.
  const double sx = static_cast<double>(width_) / out_width;
  const double sy = static_cast<double>(height_) / out_height;
  std::vector<float> columns(static_cast<size_t>(3) * out_width * height_);
  for (int ox = 0; ox < out_width; ++ox) {
    const double left = ox * sx;
    const double right = left + sx;
    for (int x = static_cast<int>(left); x < width_ && x < right; ++x) {
      const double weight = (std::min<double>(x + 1, right) - std::max<double>(x, left)) / sx;
      for (int y = 0; y < height_; ++y) {
        const uint8_t* p = pixels_.data() + 3 * (static_cast<size_t>(y) * width_ + x);
        float* c = columns.data() + 3 * (static_cast<size_t>(y) * out_width + ox);
        c[0] += static_cast<float>(weight * p[0]);
        c[1] += static_cast<float>(weight * p[1]);
        c[2] += static_cast<float>(weight * p[2]);
      }
    }
  }
  std::fill(out.begin(), out.end(), 0);
  std::vector<float> row(static_cast<size_t>(3) * out_width);
  for (int oy = 0; oy < out_height; ++oy) {
    std::fill(row.begin(), row.end(), 0.0f);
    const double top = oy * sy;
    const double bottom = top + sy;
    for (int y = static_cast<int>(top); y < height_ && y < bottom; ++y) {
      const double weight = (std::min<double>(y + 1, bottom) - std::max<double>(y, top)) / sy;
      const float* c = columns.data() + 3 * static_cast<size_t>(y) * out_width;
      for (int i = 0; i < 3 * out_width; ++i) row[i] += static_cast<float>(weight * c[i]);
    }
    uint8_t* o = out.data() + 3 * static_cast<size_t>(oy) * out_width;
    for (int i = 0; i < 3 * out_width; ++i) {
      o[i] = static_cast<uint8_t>(std::clamp(row[i] + 1e-3f, 0.0f, 255.0f));
    }
  }
}

}  // namespace dcs::env
