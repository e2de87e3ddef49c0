// Copyright 2026 The DCS Authors.
//
// BipedalWalker::Render: Gymnasium's BipedalWalker.render on env::Canvas.

#include "env/bipedal_walker.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <numbers>

#include "env/raster.h"

namespace dcs::env {
namespace {

constexpr Rgb kSky = {215, 215, 255};
constexpr Rgb kCloud = {255, 255, 255};
constexpr Rgb kTerrainFill = {102, 153, 76};
constexpr Rgb kObstacleFill = {255, 255, 255};
constexpr Rgb kObstacleLine = {153, 153, 153};
constexpr Rgb kLidar = {255, 0, 0};
constexpr Rgb kHullFill = {127, 51, 229};
constexpr Rgb kHullLine = {76, 76, 127};
// Leg colours (153 - 25 i, 76 - 25 i, 127 - 25 i) and (102 - 25 i, 51 - 25 i, 76 - 25 i).
constexpr std::array<Rgb, 2> kLegFill = {Rgb{178, 101, 152}, Rgb{128, 51, 102}};
constexpr std::array<Rgb, 2> kLegLine = {Rgb{127, 76, 101}, Rgb{77, 26, 51}};
constexpr Rgb kFlag = {230, 51, 0};
constexpr Rgb kBlack = {0, 0, 0};
constexpr int kCircleVertices = 32;

// World metres to canvas pixels: the view's left edge at `left` m, y up from the bottom row.
class View {
 public:
  View(double left, double scale, int height) : left_(left), scale_(scale), height_(height) {}
  PixelPoint operator()(double x, double y) const {
    return {(x - left_) * scale_, height_ - y * scale_};
  }
  PixelPoint operator()(const b2Vec2& p) const { return (*this)(p.x, p.y); }

 private:
  double left_;
  double scale_;
  int height_;
};

void DrawOutline(Canvas& canvas, std::span<const PixelPoint> path, Rgb color) {
  for (size_t i = 0, j = path.size() - 1; i < path.size(); j = i++) {
    canvas.DrawLine(path[j], path[i], color);
  }
}

// Every polygon fixture of `body`, filled and outlined; circles filled in the outline colour
// (pygame draws a circle twice, filled, the outline colour last).
void DrawBody(Canvas& canvas, const View& view, const b2Body& body, Rgb fill, Rgb line) {
  const b2Transform& transform = body.GetTransform();
  std::array<PixelPoint, kCircleVertices> path;
  for (const b2Fixture* f = body.GetFixtureList(); f != nullptr; f = f->GetNext()) {
    if (f->GetType() == b2Shape::e_polygon) {
      const auto* polygon = static_cast<const b2PolygonShape*>(f->GetShape());
      const int n = polygon->m_count;
      for (int i = 0; i < n; ++i) path[i] = view(b2Mul(transform, polygon->m_vertices[i]));
      canvas.FillPolygon(std::span(path.data(), n), fill);
      DrawOutline(canvas, std::span(path.data(), n), line);
    } else if (f->GetType() == b2Shape::e_circle) {
      const auto* circle = static_cast<const b2CircleShape*>(f->GetShape());
      const b2Vec2 center = b2Mul(transform, circle->m_p);
      for (int i = 0; i < kCircleVertices; ++i) {
        const double a = 2 * std::numbers::pi * i / kCircleVertices;
        path[i] = view(center.x + circle->m_radius * std::cos(a),
                       center.y + circle->m_radius * std::sin(a));
      }
      canvas.FillPolygon(path, line);
    }
  }
}

}  // namespace

// Gymnasium's render order: sky, clouds, terrain fill, the lidar ray, then its drawlist
// (terrain bodies in reverse creation order, legs, hull), then the flag.
void BipedalWalker::Render(Canvas& canvas, int lidar_ray) const {
  assert(built_);
  const WalkerWorld& world = *world_;
  const WalkerGeometry& geometry = world.geometry();
  const double scale = scale_;
  const double view_width = canvas.width() / scale;  // m
  const View view(std::max(0.0, scroll_), scale, canvas.height());

  canvas.Clear(kSky);
  std::array<PixelPoint, 5> cloud;
  for (const WalkerWorld::Cloud& c : world.clouds()) {
    if (c.x2 < scroll_ / 2 || c.x1 > scroll_ / 2 + view_width) continue;
    for (size_t i = 0; i < cloud.size(); ++i) {
      cloud[i] = view(c.vertices[i].x + scroll_ / 2, c.vertices[i].y);
    }
    canvas.FillPolygon(cloud, kCloud);
  }

  const std::span<const double> xs = world.terrain_x();
  const std::span<const double> ys = world.terrain_y();
  for (size_t i = 0; i + 1 < xs.size(); ++i) {
    if (xs[i + 1] < scroll_ || xs[i] > scroll_ + view_width) continue;
    const std::array<PixelPoint, 4> fill = {view(xs[i], ys[i]), view(xs[i + 1], ys[i + 1]),
                                            view(xs[i + 1], 0), view(xs[i], 0)};
    canvas.FillPolygon(fill, kTerrainFill);
  }

  if (lidar_ray >= 0 && lidar_ray < WalkerWorld::kNumLidar) {
    const WalkerWorld::LidarRay& ray = world.lidar(lidar_ray);
    canvas.DrawLine(view(ray.p1), view(ray.p2), kLidar);
  }

  for (size_t i = xs.size() - 1; i-- > 0;) {
    if (xs[i + 1] < scroll_ || xs[i] > scroll_ + view_width) continue;
    const Rgb color = {76, static_cast<uint8_t>(i % 2 == 0 ? 255 : 204), 76};
    canvas.DrawLine(view(xs[i], ys[i]), view(xs[i + 1], ys[i + 1]), color);
  }
  const std::span<const WalkerWorld::Obstacle> obstacles = world.obstacles();
  for (auto it = obstacles.rbegin(); it != obstacles.rend(); ++it) {
    std::array<PixelPoint, 4> path;
    for (size_t i = 0; i < path.size(); ++i) path[i] = view(it->vertices[i]);
    canvas.FillPolygon(path, kObstacleFill);
    DrawOutline(canvas, path, kObstacleLine);
  }

  for (int i = 0; i < WalkerWorld::kNumLegs; ++i) {
    DrawBody(canvas, view, *world.leg(i), kLegFill[i / 2], kLegLine[i / 2]);
  }
  DrawBody(canvas, view, *world.hull(), kHullFill, kHullLine);

  // The start flag, in pixels above the ground line.
  const double flag_x = geometry.terrain_step * 3;
  const double y1 = geometry.terrain_height;
  const double y2 = y1 + 50 / scale;
  canvas.DrawLine(view(flag_x, y1), view(flag_x, y2), kBlack);
  const std::array<PixelPoint, 3> flag = {view(flag_x, y2), view(flag_x, y2 - 10 / scale),
                                          view(flag_x + 25 / scale, y2 - 5 / scale)};
  canvas.FillPolygon(flag, kFlag);
  DrawOutline(canvas, flag, kBlack);
}

}  // namespace dcs::env
