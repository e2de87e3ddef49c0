// Copyright 2026 The DCS Authors.
#include "env/car_racing_render.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace dcs::env {
namespace {

// Gymnasium's window and camera (car_racing.py).
constexpr double kWindowW = 1000;
constexpr double kWindowH = 800;
constexpr double kZoom = 2.7;
constexpr double kGrassDim = kPlayfield / 20.0;

constexpr Rgb kBlack = {0, 0, 0};
constexpr Rgb kWheelStripe = {77, 77, 77};
constexpr Rgb kHullColor = {204, 0, 0};
constexpr Rgb kPayloadColor = {0, 255, 255};

// World -> canvas: Gymnasium's P = (500, 200) + zoom * R(-hull angle) * (p - hull position),
// truncated toward zero like pygame, then the vertical flip and the canvas scale. An integer
// pygame pixel coordinate k is the centre of pixel k, so it maps to k + 0.5 (flipped: 799.5 - k)
// in continuous coordinates.
class View {
 public:
  View(const b2Body& hull, double time, double sx, double sy) : sx_(sx), sy_(sy) {
    const b2Vec2 position = hull.GetPosition();
    hx_ = position.x;
    hy_ = position.y;
    const double angle = -static_cast<double>(hull.GetAngle());
    c_ = std::cos(angle);
    s_ = std::sin(angle);
    zoom_ = 0.1 * kCarRacingScale * std::max(1 - time, 0.0) +
            kZoom * kCarRacingScale * std::min(time, 1.0);
  }

  PixelPoint Map(double x, double y) const {
    const double dx = x - hx_;
    const double dy = y - hy_;
    const double px = std::trunc(kWindowW / 2 + zoom_ * (dx * c_ - dy * s_));
    const double py = std::trunc(kWindowH / 4 + zoom_ * (dx * s_ + dy * c_));
    return {(px + 0.5) * sx_, (kWindowH - 0.5 - py) * sy_};
  }

  // The world point shown at pre-flip window pixel (px, py), without truncation.
  WorldPoint Unmap(double px, double py) const {
    const double u = (px - kWindowW / 2) / zoom_;
    const double v = (py - kWindowH / 4) / zoom_;
    // Inverse rotation R(angle)^T.
    return {hx_ + u * c_ + v * s_, hy_ - u * s_ + v * c_};
  }

 private:
  double hx_ = 0;
  double hy_ = 0;
  double c_ = 1;
  double s_ = 0;
  double zoom_ = 1;
  double sx_;
  double sy_;
};

// Canvas::Clear writes pixel by pixel; this fills the first row and copies it (the canvas is
// cleared at every step).
void FastClear(Canvas& canvas, Rgb color) {
  const std::span<uint8_t> pixels = canvas.pixels();
  const size_t row = 3 * static_cast<size_t>(canvas.width());
  for (size_t i = 0; i < row; i += 3) {
    pixels[i] = color.r;
    pixels[i + 1] = color.g;
    pixels[i + 2] = color.b;
  }
  for (size_t offset = row; offset < pixels.size(); offset += row) {
    std::memcpy(pixels.data() + offset, pixels.data(), row);
  }
}

// Fills a mapped polygon unless its bounding box misses the canvas.
void FillCulled(Canvas& canvas, std::span<const PixelPoint> points, Rgb color) {
  double min_x = points[0].x;
  double max_x = points[0].x;
  double min_y = points[0].y;
  double max_y = points[0].y;
  for (const PixelPoint& p : points.subspan(1)) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y);
    max_y = std::max(max_y, p.y);
  }
  if (max_x < 0 || max_y < 0 || min_x > canvas.width() || min_y > canvas.height()) return;
  canvas.FillPolygon(points, color);
}

// Draws every polygon fixture of `body` in `color` (at most 8 vertices each).
void DrawBody(const View& view, const b2Body& body, Rgb color, Canvas& canvas) {
  const b2Transform& xf = body.GetTransform();
  for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
    if (f->GetType() != b2Shape::e_polygon) continue;
    const auto* shape = static_cast<const b2PolygonShape*>(f->GetShape());
    std::array<PixelPoint, b2_maxPolygonVertices> points;
    for (int i = 0; i < shape->m_count; ++i) {
      const b2Vec2 p = b2Mul(xf, shape->m_vertices[i]);
      points[i] = view.Map(p.x, p.y);
    }
    FillCulled(canvas, std::span<const PixelPoint>(points.data(), shape->m_count), color);
  }
}

double Sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

void DrawWheelStripe(const View& view, const Car::Wheel& wheel, Canvas& canvas) {
  const double a1 = wheel.phase;
  const double a2 = wheel.phase + 1.2;
  const double s1 = std::sin(a1);
  const double s2 = std::sin(a2);
  double c1 = std::cos(a1);
  double c2 = std::cos(a2);
  if (s1 > 0 && s2 > 0) return;
  if (s1 > 0) c1 = Sign(c1);
  if (s2 > 0) c2 = Sign(c2);
  constexpr double kW = 14;
  constexpr double kR = 27;
  const double local[4][2] = {{-kW * kCarSize, +kR * c1 * kCarSize},
                              {+kW * kCarSize, +kR * c1 * kCarSize},
                              {+kW * kCarSize, +kR * c2 * kCarSize},
                              {-kW * kCarSize, +kR * c2 * kCarSize}};
  const b2Transform& xf = wheel.body->GetTransform();
  std::array<PixelPoint, 4> points;
  for (int i = 0; i < 4; ++i) {
    const b2Vec2 p =
        b2Mul(xf, b2Vec2(static_cast<float>(local[i][0]), static_cast<float>(local[i][1])));
    points[i] = view.Map(p.x, p.y);
  }
  FillCulled(canvas, points, kWheelStripe);
}

// A pygame.draw.polygon rectangle after the flip, in window pixels: corners truncated, spans
// inclusive, so it covers [min, max + 1) in continuous coordinates.
void FillWindowRect(Canvas& canvas, double x0, double y0, double x1, double y1, Rgb color) {
  const double sx = canvas.width() / kWindowW;
  const double sy = canvas.height() / kWindowH;
  x0 = std::trunc(x0);
  x1 = std::trunc(x1);
  y0 = std::trunc(y0);
  y1 = std::trunc(y1);
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  canvas.FillRect(x0 * sx, y0 * sy, (x1 + 1) * sx, (y1 + 1) * sy, color);
}

// Gymnasium's _render_indicators, on the flipped window (s = 25, h = 20).
void DrawIndicators(const Car& car, Canvas& canvas) {
  constexpr double s = kWindowW / 40.0;
  constexpr double h = kWindowH / 40.0;
  constexpr double H = kWindowH;
  FillWindowRect(canvas, 0, H - 5 * h, kWindowW, H, kBlack);
  auto vertical_ind = [&](double place, double val, double quantity, Rgb color) {
    if (std::abs(quantity) <= 1e-4) return;
    FillWindowRect(canvas, place * s, H - (h + h * val), (place + 1) * s, H - h, color);
  };
  auto horiz_ind = [&](double place, double val, double quantity, Rgb color) {
    if (std::abs(quantity) <= 1e-4) return;
    FillWindowRect(canvas, place * s, H - 4 * h, (place + val) * s, H - 2 * h, color);
  };
  const b2Vec2 velocity = car.hull()->GetLinearVelocity();
  const double vx = velocity.x;
  const double vy = velocity.y;
  const double true_speed = std::sqrt(vx * vx + vy * vy);
  vertical_ind(5, 0.02 * true_speed, true_speed, {255, 255, 255});
  const std::array<Car::Wheel, 4>& wheels = car.wheels();
  vertical_ind(7, 0.01 * wheels[0].omega, wheels[0].omega, {0, 0, 255});
  vertical_ind(8, 0.01 * wheels[1].omega, wheels[1].omega, {0, 0, 255});
  vertical_ind(9, 0.01 * wheels[2].omega, wheels[2].omega, {51, 0, 255});
  vertical_ind(10, 0.01 * wheels[3].omega, wheels[3].omega, {51, 0, 255});
  const double steer_angle = wheels[0].joint->GetJointAngle();
  horiz_ind(20, -10.0 * steer_angle, steer_angle, {0, 255, 0});
  const double gyro = car.hull()->GetAngularVelocity();
  horiz_ind(30, -0.8 * gyro, gyro, {255, 0, 0});
}

// 5x7 glyphs, one byte per row, bit 4 = leftmost column.
constexpr uint8_t kDigitGlyphs[10][7] = {
    {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}, {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E},
    {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}, {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E},
    {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}, {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E},
    {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}, {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08},
    {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}, {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}};
constexpr uint8_t kMinusGlyph[7] = {0, 0, 0, 0x1F, 0, 0, 0};

// The score in white, centred at window (60, 750): glyph cells of 23.35 px (FreeSansBold's
// digit advance at 42 px), ink 20 x 30 px from y = 733.
void DrawScore(double score, Canvas& canvas) {
  char text[32];
  const int n = std::snprintf(text, sizeof(text), "%04.0f", score);
  if (n <= 0 || n >= static_cast<int>(sizeof(text))) return;
  constexpr double kAdvance = 23.35;
  constexpr double kCellW = 4.0;
  constexpr double kCellH = 30.0 / 7;
  constexpr double kTop = 733;
  const double sx = canvas.width() / kWindowW;
  const double sy = canvas.height() / kWindowH;
  double left = 60 - kAdvance * n / 2 + 1.7;
  for (int i = 0; i < n; ++i, left += kAdvance) {
    const uint8_t* glyph = nullptr;
    if (text[i] >= '0' && text[i] <= '9') glyph = kDigitGlyphs[text[i] - '0'];
    if (text[i] == '-') glyph = kMinusGlyph;
    if (glyph == nullptr) continue;
    for (int row = 0; row < 7; ++row) {
      for (int col = 0; col < 5; ++col) {
        if ((glyph[row] >> (4 - col) & 1) == 0) continue;
        const double x0 = left + col * kCellW;
        const double y0 = kTop + row * kCellH;
        canvas.FillRect(x0 * sx, y0 * sy, (x0 + kCellW) * sx, (y0 + kCellH) * sy, {255, 255, 255});
      }
    }
  }
}

// Shrinks the (96 K)^2 canvas to 96x96: the mean of each K x K block, rounded down. Rows are
// summed first (contiguous, vectorisable), then K neighbouring pixels of the row sums.
template <int K>
void BoxFilter(const uint8_t* pixels,
               std::span<uint8_t, CarRacingObservationRenderer::kSize *
                                      CarRacingObservationRenderer::kSize * 3>
                   out) {
  constexpr int kSize = CarRacingObservationRenderer::kSize;
  constexpr int kRowBytes = 3 * kSize * K;
  // floor(sum / K^2) as a multiply and shift: exact because sum * K^2 < 2^32.
  constexpr uint64_t kReciprocal = ((uint64_t{1} << 32) + K * K - 1) / (K * K);
  std::array<uint16_t, kRowBytes> rows;
  for (int oy = 0; oy < kSize; ++oy) {
    const uint8_t* row = pixels + static_cast<size_t>(oy) * K * kRowBytes;
    for (int i = 0; i < kRowBytes; ++i) rows[i] = row[i];
    for (int dy = 1; dy < K; ++dy) {
      row += kRowBytes;
      for (int i = 0; i < kRowBytes; ++i) rows[i] = static_cast<uint16_t>(rows[i] + row[i]);
    }
    uint8_t* o = out.data() + static_cast<size_t>(oy) * kSize * 3;
    for (int ox = 0; ox < kSize; ++ox) {
      for (int c = 0; c < 3; ++c) {
        uint32_t sum = 0;
        for (int dx = 0; dx < K; ++dx) sum += rows[3 * (ox * K + dx) + c];
        o[3 * ox + c] = static_cast<uint8_t>(sum * kReciprocal >> 32);
      }
    }
  }
}

}  // namespace

void DrawCarRacingFrame(const CarRacingFrame& frame, Canvas& canvas) {
  assert(frame.car != nullptr);
  const Car& car = *frame.car;
  const double sx = canvas.width() / kWindowW;
  const double sy = canvas.height() / kWindowH;
  const View view(*car.hull(), frame.time, sx, sy);

  // The world rectangle the window shows, and its bounding box.
  const WorldPoint corners[4] = {view.Unmap(0, 0), view.Unmap(kWindowW, 0), view.Unmap(0, kWindowH),
                                 view.Unmap(kWindowW, kWindowH)};
  double min_x = corners[0].x;
  double max_x = corners[0].x;
  double min_y = corners[0].y;
  double max_y = corners[0].y;
  for (const WorldPoint& p : corners) {
    min_x = std::min(min_x, p.x);
    max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y);
    max_y = std::max(max_y, p.y);
  }

  // 1. The playfield square in the background colour, black outside it. A small margin keeps
  // the shortcut exact despite the truncation of the square's corners.
  const double inside = kPlayfield - 1;
  if (min_x >= -inside && max_x <= inside && min_y >= -inside && max_y <= inside) {
    FastClear(canvas, frame.colors.background);
  } else {
    FastClear(canvas, kBlack);
    const PixelPoint field[4] = {
        view.Map(kPlayfield, kPlayfield), view.Map(kPlayfield, -kPlayfield),
        view.Map(-kPlayfield, -kPlayfield), view.Map(-kPlayfield, kPlayfield)};
    canvas.FillPolygon(field, frame.colors.background);
  }

  // 2. Grass patches on the even-even cells of a 40x40 grid, those near the view only.
  const double g = kGrassDim;
  for (int ix = -20; ix < 20; ix += 2) {
    if ((ix + 1) * g < min_x - 1 || ix * g > max_x + 1) continue;
    for (int iy = -20; iy < 20; iy += 2) {
      if ((iy + 1) * g < min_y - 1 || iy * g > max_y + 1) continue;
      const PixelPoint patch[4] = {
          view.Map(g * ix + g, g * iy + 0), view.Map(g * ix + 0, g * iy + 0),
          view.Map(g * ix + 0, g * iy + g), view.Map(g * ix + g, g * iy + g)};
      FillCulled(canvas, patch, frame.colors.grass);
    }
  }

  // 3. Road tiles, each followed by its kerb.
  for (const RoadPolygon& polygon : frame.road) {
    const WorldPoint* p = polygon.points.data();
    // Cheap world-space rejection before mapping.
    const double px_min = std::min({p[0].x, p[1].x, p[2].x, p[3].x});
    const double px_max = std::max({p[0].x, p[1].x, p[2].x, p[3].x});
    const double py_min = std::min({p[0].y, p[1].y, p[2].y, p[3].y});
    const double py_max = std::max({p[0].y, p[1].y, p[2].y, p[3].y});
    if (px_max < min_x - 1 || px_min > max_x + 1 || py_max < min_y - 1 || py_min > max_y + 1) {
      continue;
    }
    const PixelPoint points[4] = {view.Map(p[0].x, p[0].y), view.Map(p[1].x, p[1].y),
                                  view.Map(p[2].x, p[2].y), view.Map(p[3].x, p[3].y)};
    const Rgb color = polygon.tile >= 0 ? frame.tile_colors[polygon.tile] : polygon.color;
    FillCulled(canvas, points, color);
  }

  // 4. The car: wheels (black, then the stripe), hull, payload.
  for (const Car::Wheel& wheel : car.wheels()) {
    DrawBody(view, *wheel.body, kBlack, canvas);
    DrawWheelStripe(view, wheel, canvas);
  }
  DrawBody(view, *car.hull(), kHullColor, canvas);
  if (car.payload() != nullptr) DrawBody(view, *car.payload(), kPayloadColor, canvas);

  // 5. Indicators and score, on the flipped picture.
  DrawIndicators(car, canvas);
  DrawScore(frame.score, canvas);
}

CarRacingObservationRenderer::CarRacingObservationRenderer(int supersample)
    : supersample_(supersample), canvas_(kSize * supersample, kSize * supersample) {
  assert(supersample >= 1 && supersample <= 8);
}

void CarRacingObservationRenderer::Render(const CarRacingFrame& frame,
                                          std::span<uint8_t, kSize * kSize * 3> observation) {
  DrawCarRacingFrame(frame, canvas_);
  const uint8_t* pixels = canvas_.pixels().data();
  switch (supersample_) {
    case 1:
      std::memcpy(observation.data(), pixels, observation.size());
      break;
    case 2:
      BoxFilter<2>(pixels, observation);
      break;
    case 3:
      BoxFilter<3>(pixels, observation);
      break;
    case 4:
      BoxFilter<4>(pixels, observation);
      break;
    case 5:
      BoxFilter<5>(pixels, observation);
      break;
    case 6:
      BoxFilter<6>(pixels, observation);
      break;
    case 7:
      BoxFilter<7>(pixels, observation);
      break;
    default:
      BoxFilter<8>(pixels, observation);
      break;
  }
}

}  // namespace dcs::env
