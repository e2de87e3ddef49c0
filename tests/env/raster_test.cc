// Copyright 2026 The DCS Authors.
#include "env/raster.h"

#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

constexpr Rgb kWhite = {255, 255, 255};
constexpr Rgb kRed = {255, 0, 0};

bool IsRed(const Canvas& canvas, int x, int y) {
  const uint8_t* p = canvas.pixels().data() + 3 * (y * canvas.width() + x);
  return p[0] == 255 && p[1] == 0 && p[2] == 0;
}

int CountRed(const Canvas& canvas) {
  int count = 0;
  for (int y = 0; y < canvas.height(); ++y) {
    for (int x = 0; x < canvas.width(); ++x) count += IsRed(canvas, x, y);
  }
  return count;
}

TEST(CanvasTest, FillsExactlyThePixelsWhoseCentresAreInside) {
  Canvas canvas(10, 10);
  canvas.Clear(kWhite);
  const PixelPoint square[] = {{2, 3}, {6, 3}, {6, 7}, {2, 7}};
  canvas.FillPolygon(square, kRed);
  EXPECT_EQ(CountRed(canvas), 16);
  EXPECT_TRUE(IsRed(canvas, 2, 3));
  EXPECT_TRUE(IsRed(canvas, 5, 6));
  EXPECT_FALSE(IsRed(canvas, 6, 6));
  EXPECT_FALSE(IsRed(canvas, 1, 3));
}

TEST(CanvasTest, TriangleCoversHalfOfItsBox) {
  Canvas canvas(100, 100);
  canvas.Clear(kWhite);
  const PixelPoint triangle[] = {{0, 0}, {100, 0}, {0, 100}};
  canvas.FillPolygon(triangle, kRed);
  // Pixel (x, y) is inside when x + 0.5 < 100 - (y + 0.5): 100 * 99 / 2 pixels.
  EXPECT_EQ(CountRed(canvas), 4950);
  EXPECT_TRUE(IsRed(canvas, 0, 98));
  EXPECT_FALSE(IsRed(canvas, 1, 98));
}

TEST(CanvasTest, ConcavePolygonLeavesItsNotchEmpty) {
  Canvas canvas(10, 10);
  canvas.Clear(kWhite);
  // A "U": the notch [4, 6) x [0, 6) stays white.
  const PixelPoint u[] = {{2, 0}, {4, 0}, {4, 6}, {6, 6}, {6, 0}, {8, 0}, {8, 8}, {2, 8}};
  canvas.FillPolygon(u, kRed);
  EXPECT_FALSE(IsRed(canvas, 4, 2));
  EXPECT_FALSE(IsRed(canvas, 5, 5));
  EXPECT_TRUE(IsRed(canvas, 5, 6));
  EXPECT_TRUE(IsRed(canvas, 3, 2));
  EXPECT_TRUE(IsRed(canvas, 7, 2));
  EXPECT_EQ(CountRed(canvas), 6 * 8 - 2 * 6);
}

TEST(CanvasTest, ClipsToTheCanvas) {
  Canvas canvas(10, 10);
  canvas.Clear(kWhite);
  const PixelPoint big[] = {{-50, -50}, {50, -50}, {50, 5}, {-50, 5}};
  canvas.FillPolygon(big, kRed);
  EXPECT_EQ(CountRed(canvas), 50);  // the top 5 rows
  canvas.FillRect(20, 20, 30, 30, kWhite);  // wholly outside: nothing happens
  EXPECT_EQ(CountRed(canvas), 50);
}

TEST(CanvasTest, RectangleCornersMayComeInAnyOrder) {
  Canvas canvas(10, 10);
  canvas.Clear(kWhite);
  canvas.FillRect(7, 6, 3, 2, kRed);
  EXPECT_EQ(CountRed(canvas), 16);
  EXPECT_TRUE(IsRed(canvas, 3, 2));
  EXPECT_FALSE(IsRed(canvas, 7, 6));
}

TEST(CanvasTest, LineColoursBothEnds) {
  Canvas canvas(10, 10);
  canvas.Clear(kWhite);
  canvas.DrawLine({0.5, 0.5}, {9.5, 4.5}, kRed);
  EXPECT_TRUE(IsRed(canvas, 0, 0));
  EXPECT_TRUE(IsRed(canvas, 9, 4));
  EXPECT_EQ(CountRed(canvas), 10);  // one pixel per column of a shallow line
}

TEST(CanvasTest, DownscaleAveragesAreas) {
  Canvas canvas(4, 4);
  canvas.Clear({0, 0, 0});
  canvas.FillRect(0, 0, 2, 4, kWhite);  // left half white
  std::vector<uint8_t> out(3 * 2 * 2);
  canvas.Downscale(2, 2, out);
  EXPECT_THAT(out, ::testing::ElementsAre(255, 255, 255, 0, 0, 0, 255, 255, 255, 0, 0, 0));

  // 3 pixels into 2: each output pixel averages one whole and half of the middle one.
  Canvas row(3, 1);
  row.Clear({0, 0, 0});
  row.FillRect(0, 0, 1, 1, {90, 90, 90});
  row.FillRect(1, 0, 2, 1, {30, 30, 30});
  std::vector<uint8_t> shrunk(3 * 2);
  row.Downscale(2, 1, shrunk);
  EXPECT_EQ(shrunk[0], 70);  // (90 * 1 + 30 * 0.5) / 1.5
  EXPECT_EQ(shrunk[3], 10);  // (30 * 0.5 + 0 * 1) / 1.5
}

}  // namespace
}  // namespace dcs::env
