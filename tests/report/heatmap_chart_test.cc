// Copyright 2026 The DCS Authors.
#include "report/heatmap_chart.h"

#include <limits>
#include <string>
#include <vector>

#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> Lines(const std::string& text) {
  return absl::StrSplit(text, '\n', absl::SkipEmpty());
}

Heatmap Families() {
  return {.name = "families",
          .title = "Relative to static",
          .x_label = "observe mode",
          .y_label = "family",
          .column_labels = {"none", "live"},
          .row_labels = {"sinusoidal", "random_walk"},
          .values = {{12.34, -40}, {kNaN, 3}},
          .value_label = "difference"};
}

GnuplotFigure MustBuild(const Heatmap& heatmap) {
  absl::StatusOr<GnuplotFigure> figure = HeatmapFigure(heatmap);
  EXPECT_TRUE(figure.ok()) << figure.status();
  return figure.ok() ? *figure : GnuplotFigure{};
}

TEST(HeatmapFigureTest, WritesACellPerRowWithItsTextAndTextColour) {
  const GnuplotFigure figure = MustBuild(Families());
  ASSERT_EQ(figure.data.size(), 1u);
  EXPECT_EQ(figure.data[0].name, "families.csv");
  // The scale spans [-40, 40]: |-40| > 60% of it takes white text.
  EXPECT_THAT(Lines(figure.data[0].csv),
              ElementsAre("row,column,value,text_color,text,row_label,column_label",
                          "0,0,12.34,0,+12.3,sinusoidal,none",
                          "0,1,-40,16777215,-40.0,sinusoidal,live",
                          "1,0,,0,n/a,random_walk,none", "1,1,3,0,+3.0,random_walk,live"));
}

TEST(HeatmapFigureTest, CentresADivergingPaletteAtZeroAndLabelsTheAxes) {
  const std::string script = MustBuild(Families()).script;
  EXPECT_THAT(script, HasSubstr("set palette defined (-1 '#D55E00', 0 '#f7f7f7', 1 '#0072B2')"));
  EXPECT_THAT(script, HasSubstr("set cbrange [-40:40]"));
  EXPECT_THAT(script, HasSubstr("set xtics ('none' 0, 'live' 1) scale 0"));
  EXPECT_THAT(script, HasSubstr("set ytics ('sinusoidal' 0, 'random_walk' 1) scale 0"));
  EXPECT_THAT(script, HasSubstr("set yrange [1.5:-0.5]"));  // the first row on top
  EXPECT_THAT(script, HasSubstr("set xlabel 'observe mode'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'family'"));
  EXPECT_THAT(script, HasSubstr("set cblabel 'difference'"));
  EXPECT_THAT(script, HasSubstr("set title 'Relative to static'"));
  EXPECT_THAT(script, HasSubstr("with boxxyerror fc palette"));
  EXPECT_THAT(script, HasSubstr("with labels textcolor rgb variable"));
}

TEST(HeatmapFigureTest, PrintsTheAskedDecimals) {
  Heatmap heatmap = Families();
  heatmap.decimals = 0;
  EXPECT_THAT(MustBuild(heatmap).data[0].csv, HasSubstr(",+12,"));
}

TEST(HeatmapFigureTest, ScalesToOneWithoutValues) {
  Heatmap heatmap = Families();
  heatmap.values = {{kNaN, 0}, {kNaN, kNaN}};
  EXPECT_THAT(MustBuild(heatmap).script, HasSubstr("set cbrange [-1:1]"));
}

TEST(HeatmapFigureTest, EscapesLabels) {
  Heatmap heatmap = Families();
  heatmap.row_labels[0] = "a'b, c";
  const GnuplotFigure figure = MustBuild(heatmap);
  EXPECT_THAT(figure.script, HasSubstr("('a''b, c' 0,"));
  EXPECT_THAT(figure.data[0].csv, HasSubstr(",\"a'b, c\",none"));
}

TEST(HeatmapFigureTest, RefusesBadHeatmaps) {
  auto code = [](const Heatmap& heatmap) { return HeatmapFigure(heatmap).status().code(); };
  const auto kBad = absl::StatusCode::kInvalidArgument;
  Heatmap heatmap = Families();
  heatmap.name = "bad name";
  EXPECT_EQ(code(heatmap), kBad);
  heatmap = Families();
  heatmap.column_labels.clear();
  EXPECT_EQ(code(heatmap), kBad);
  heatmap = Families();
  heatmap.values.pop_back();
  EXPECT_EQ(code(heatmap), kBad);
  heatmap = Families();
  heatmap.values[1].push_back(1);
  EXPECT_EQ(code(heatmap), kBad);
  heatmap = Families();
  heatmap.values[0][0] = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(code(heatmap), kBad);
  heatmap = Families();
  heatmap.decimals = 7;
  EXPECT_EQ(code(heatmap), kBad);
}

}  // namespace
}  // namespace dcs::report
