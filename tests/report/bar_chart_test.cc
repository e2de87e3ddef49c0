// Copyright 2026 The DCS Authors.
#include "report/bar_chart.h"

#include <limits>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> Lines(const std::string& text) {
  return absl::StrSplit(text, '\n', absl::SkipEmpty());
}

int Count(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

// Two series over three contexts in two groups: low | id id.
BarChart Contexts() {
  return {.name = "contexts",
          .title = "Per context",
          .panels = {{.title = "observe: none",
                      .x_label = "context",
                      .y_label = "return",
                      .categories = {{"0.1", "OOD-low"}, {"0.4", "ID"}, {"0.6", "ID"}},
                      .series = {{.label = "sinusoidal",
                                  .y = {10, 20, kNaN},
                                  .y_low = {8, 18, kNaN},
                                  .y_high = {12, 22, kNaN}},
                                 {.label = "static", .y = {5, 15, 25}, .color = "#000000"}}}}};
}

GnuplotFigure MustBuild(const BarChart& chart) {
  absl::StatusOr<GnuplotFigure> figure = BarChartFigure(chart);
  EXPECT_TRUE(figure.ok()) << figure.status();
  return figure.ok() ? *figure : GnuplotFigure{};
}

TEST(BarChartFigureTest, WritesARowPerBarAtItsPosition) {
  const GnuplotFigure figure = MustBuild(Contexts());
  ASSERT_EQ(figure.data.size(), 1u);
  EXPECT_EQ(figure.data[0].name, "contexts.csv");
  // Clusters at 0 (OOD-low), then 1.6 and 2.6 (ID, after a gap); two bars of width 0.4 each.
  EXPECT_THAT(Lines(figure.data[0].csv),
              ElementsAre("panel,series,category,x,y,y_low,y_high,group,category_label,label",
                          "0,0,0,-0.2,10,8,12,OOD-low,0.1,sinusoidal",
                          "0,0,1,1.4,20,18,22,ID,0.4,sinusoidal",
                          "0,1,0,0.2,5,,,OOD-low,0.1,static", "0,1,1,1.8,15,,,ID,0.4,static",
                          "0,1,2,2.8,25,,,ID,0.6,static"));
}

TEST(BarChartFigureTest, PlotsBarsAndErrorBarsPerSeriesUnderGroupNames) {
  const std::string script = MustBuild(Contexts()).script;
  EXPECT_THAT(script, HasSubstr("set xtics ('0.1' 0, '0.4' 1.6, '0.6' 2.6)"));
  EXPECT_THAT(script, HasSubstr("set label 'OOD-low' at first 0, graph 0.95 center"));
  EXPECT_THAT(script, HasSubstr("set label 'ID' at first 2.1, graph 0.95 center"));
  EXPECT_THAT(script, HasSubstr("set arrow from first 0.8, graph 0 to first 0.8, graph 1"));
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(0, 0, 'y')):(0.368) with boxes fc rgb "
                                "'#0072B2' fs solid 0.85 noborder title 'sinusoidal'"));
  EXPECT_THAT(script, HasSubstr("with boxes fc rgb '#000000' fs solid 0.85 noborder title "
                                "'static'"));
  EXPECT_EQ(Count(script, "with boxes"), 2);
  EXPECT_EQ(Count(script, "with vectors nohead"), 1);  // the series with error bars
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(0, 0, 'y_low')):(0):(sel(0, 0, 'y_high') - "
                                "sel(0, 0, 'y_low')) with vectors nohead"));
  EXPECT_THAT(script, HasSubstr("set xlabel 'context'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'return'"));
  // From 0 to the highest error bar or bar (25), with 16% of room for the group names.
  EXPECT_THAT(script, HasSubstr("set yrange [0:29]"));
}

TEST(BarChartFigureTest, ReachesBelowZeroForNegativeBars) {
  BarChart chart = Contexts();
  chart.panels[0].series[1].y = {-10, 15, 30};
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set yrange [-11.2:36.4]"));
  EXPECT_THAT(script, HasSubstr("set arrow from graph 0, first 0 to graph 1, first 0"));
}

TEST(BarChartFigureTest, EscapesLabels) {
  BarChart chart = Contexts();
  chart.panels[0].categories[0].group = "it's";
  chart.panels[0].series[0].label = "a_b, \"c\"";
  const GnuplotFigure figure = MustBuild(chart);
  EXPECT_THAT(figure.script, HasSubstr("set label 'it''s'"));
  EXPECT_THAT(figure.script, HasSubstr("title 'a_b, \"c\"'"));
  EXPECT_THAT(figure.data[0].csv, HasSubstr(",\"a_b, \"\"c\"\"\"\n"));
}

TEST(BarChartFigureTest, DrawsAnEmptyFrameForAPanelWithoutBars) {
  BarChart chart = Contexts();
  chart.panels.push_back({.title = "observe: live"});
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set multiplot layout 1,2"));
  EXPECT_THAT(script, HasSubstr("plot NaN notitle"));
  EXPECT_THAT(script, Not(HasSubstr("sel(1,")));
}

TEST(BarChartFigureTest, RefusesBadCharts) {
  auto code = [](const BarChart& chart) { return BarChartFigure(chart).status().code(); };
  const auto kBad = absl::StatusCode::kInvalidArgument;
  EXPECT_EQ(code({.name = "no_panels"}), kBad);
  BarChart chart = Contexts();
  chart.name = "";
  EXPECT_EQ(code(chart), kBad);
  chart = Contexts();
  chart.panels[0].series[1].y.pop_back();
  EXPECT_EQ(code(chart), kBad);
  chart = Contexts();
  chart.panels[0].series[0].y_low.pop_back();
  EXPECT_EQ(code(chart), kBad);
  chart = Contexts();
  chart.panels[0].series[0].y_high[0] = kNaN;  // under a bar
  EXPECT_EQ(code(chart), kBad);
  chart = Contexts();
  chart.panels[0].series[1].y[0] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(code(chart), kBad);
  chart = Contexts();
  chart.panel_height = 50;
  EXPECT_EQ(code(chart), kBad);
}

}  // namespace
}  // namespace dcs::report
