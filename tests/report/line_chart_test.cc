// Copyright 2026 The DCS Authors.
#include "report/line_chart.h"

#include <cmath>
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

std::vector<std::string> Lines(const std::string& text) {
  return absl::StrSplit(text, '\n', absl::SkipEmpty());
}

// The script's lines that contain `needle`.
std::vector<std::string> LinesWith(const std::string& script, const std::string& needle) {
  std::vector<std::string> found;
  for (const std::string& line : Lines(script)) {
    if (absl::StrContains(line, needle)) found.push_back(line);
  }
  return found;
}

GnuplotFigure MustBuild(const LineChart& chart) {
  absl::StatusOr<GnuplotFigure> figure = LineChartFigure(chart);
  EXPECT_TRUE(figure.ok()) << figure.status();
  return figure.ok() ? *figure : GnuplotFigure{};
}

LineChart TwoPanels() {
  return {.name = "curves",
          .title = "Two panels",
          .panels = {{.title = "none",
                      .x_label = "step",
                      .y_label = "return",
                      .lines = {{.label = "sinusoidal",
                                 .x = {0, 10},
                                 .y = {1, 2},
                                 .y_low = {0.5, 1.5},
                                 .y_high = {1.5, 2.5}},
                                {.label = "static",
                                 .x = {0, 10},
                                 .y = {3, 4},
                                 .color = "#000000",
                                 .dashed = true}}},
                     {.title = "live", .lines = {{.label = "x", .x = {5}, .y = {6}}}}}};
}

TEST(LineChartFigureTest, WritesOneCsvWithARowPerPointAndTextLast) {
  const GnuplotFigure figure = MustBuild(TwoPanels());
  EXPECT_EQ(figure.name, "curves");
  EXPECT_EQ(figure.title, "Two panels");
  ASSERT_EQ(figure.data.size(), 1u);
  EXPECT_EQ(figure.data[0].name, "curves.csv");
  EXPECT_THAT(Lines(figure.data[0].csv),
              ElementsAre("panel,line,x,y,y_low,y_high,panel_title,label",
                          "0,0,0,1,0.5,1.5,none,sinusoidal", "0,0,10,2,1.5,2.5,none,sinusoidal",
                          "0,1,0,3,,,none,static", "0,1,10,4,,,none,static",
                          "1,0,5,6,,,live,x"));
}

TEST(LineChartFigureTest, LeavesOutBandColumnsWhenNoLineHasABand) {
  LineChart chart = TwoPanels();
  chart.panels[0].lines[0].y_low.clear();
  chart.panels[0].lines[0].y_high.clear();
  const GnuplotFigure figure = MustBuild(chart);
  EXPECT_EQ(Lines(figure.data[0].csv).front(), "panel,line,x,y,panel_title,label");
}

TEST(LineChartFigureTest, PlotsEachLineFromItsRowsWithItsStyleAndTitle) {
  const std::string script = MustBuild(TwoPanels()).script;
  EXPECT_THAT(script, HasSubstr("data = 'curves.csv'"));
  EXPECT_THAT(script, HasSubstr("set multiplot layout 1,2 title 'Two panels'"));
  EXPECT_THAT(script, HasSubstr("set terminal svg size 800,316"));
  // A band, then each line, selected by panel and line index.
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(0, 0, 'y_low')):(sel(0, 0, 'y_high')) "
                                "with filledcurves fc rgb '#0072B2' fs transparent solid"));
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(0, 0, 'y')) with lines lc rgb '#0072B2' "
                                "lw 1.5 dt 1 title 'sinusoidal'"));
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(0, 1, 'y')) with lines lc rgb '#000000' "
                                "lw 1.5 dt 2 title 'static'"));
  // A line of one point is a dot.
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(1, 0, 'y')) with points pt 7"));
  EXPECT_EQ(LinesWith(script, "filledcurves").size(), 1u);
  EXPECT_EQ(LinesWith(script, "set title").size(), 2u);
  EXPECT_THAT(script, HasSubstr("set xlabel 'step'"));
  EXPECT_THAT(script, HasSubstr("set ylabel 'return'"));
  EXPECT_THAT(script, HasSubstr("unset multiplot"));
}

TEST(LineChartFigureTest, EscapesTitlesAndLabelsAsGnuplotStrings) {
  LineChart chart = TwoPanels();
  chart.title = R"(it's a "test" \n)";
  chart.panels[0].title = "x_1 ^ @ &";
  chart.panels[0].x_label = "a'b";
  chart.panels[0].lines[0].label = "one, two\nthree";
  const GnuplotFigure figure = MustBuild(chart);
  EXPECT_THAT(figure.script, HasSubstr(R"(title 'it''s a "test" \n')"));
  EXPECT_THAT(figure.script, HasSubstr("set title 'x_1 ^ @ &'"));
  EXPECT_THAT(figure.script, HasSubstr("set xlabel 'a''b'"));
  EXPECT_THAT(figure.script, HasSubstr("title 'one, two three'"));
  EXPECT_THAT(figure.data[0].csv, HasSubstr(",\"one, two\nthree\"\n"));
}

TEST(LineChartFigureTest, DrawsStepsForStepLines) {
  LineChart chart = TwoPanels();
  chart.panels[0].lines[1].steps = true;
  EXPECT_THAT(MustBuild(chart).script,
              HasSubstr("data using 'x':(sel(0, 1, 'y')) with steps lc rgb '#000000'"));
}

TEST(LineChartFigureTest, UsesFixedRangesAndDrawsOnlyMarkersInsideThem) {
  LineChart chart = TwoPanels();
  chart.panels[0].x_range = std::make_pair(0.0, 1500.0);
  chart.panels[0].y_range = std::make_pair(-1.2, 1.9);
  chart.panels[0].x_markers = {500, 1000, 2000};
  chart.panels[0].y_markers = {-1, 0, 1, 5};
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set xrange [0:1500]"));
  EXPECT_THAT(script, HasSubstr("set yrange [-1.2:1.9]"));
  EXPECT_EQ(LinesWith(script, "graph 0 to first").size(), 2u);  // x = 500 and 1000
  EXPECT_THAT(script, HasSubstr("set arrow from first 1000, graph 0 to first 1000, graph 1"));
  EXPECT_THAT(script, Not(HasSubstr("first 2000")));
  EXPECT_EQ(LinesWith(script, "set arrow from graph 0, first").size(), 3u);
  EXPECT_THAT(script, Not(HasSubstr("first 5 ")));
}

TEST(LineChartFigureTest, DrawsMarkersWithinTheDataWhenTheRangeIsAutomatic) {
  LineChart chart = TwoPanels();  // panel 0: x in [0, 10], y in [0.5, 4]
  chart.panels[0].x_markers = {5, 11};
  chart.panels[0].y_markers = {0, 1};
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set autoscale xfix"));
  EXPECT_THAT(script, HasSubstr("set arrow from first 5, graph 0"));
  EXPECT_THAT(script, Not(HasSubstr("first 11")));
  EXPECT_THAT(script, HasSubstr("set arrow from graph 0, first 1 to"));
  EXPECT_THAT(script, Not(HasSubstr("set arrow from graph 0, first 0 to")));
}

TEST(LineChartFigureTest, PlacesOrHidesTheLegend) {
  LineChart chart = TwoPanels();
  chart.panels[0].legend = LegendPlace::kBottomRight;
  chart.panels[1].lines[0].label.clear();  // nothing to list
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set key bottom right inside"));
  EXPECT_THAT(script, HasSubstr("unset key"));
  EXPECT_THAT(script, HasSubstr("data using 'x':(sel(1, 0, 'y')) with points pt 7 ps 0.6 lc "
                                "rgb '#0072B2' notitle"));
}

TEST(LineChartFigureTest, DrawsAnEmptyFrameForAPanelWithoutPoints) {
  LineChart chart = TwoPanels();
  chart.panels[1].lines = {{.label = "empty"}};
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set label 1 'no data'"));
  EXPECT_THAT(script, HasSubstr("plot NaN notitle"));
  EXPECT_THAT(script, Not(HasSubstr("sel(1, 0")));
}

std::vector<std::string> Labels(const std::vector<Tic>& tics) {
  std::vector<std::string> labels;
  for (const Tic& tic : tics) labels.push_back(tic.label);
  return labels;
}

TEST(CompactTicsTest, PicksRoundStepsWithShortLabels) {
  EXPECT_THAT(Labels(CompactTics(150000)),
              ElementsAre("0", "25k", "50k", "75k", "100k", "125k", "150k"));
  EXPECT_THAT(Labels(CompactTics(2000)), ElementsAre("0", "500", "1k", "1.5k", "2k"));
  EXPECT_THAT(Labels(CompactTics(1500000)),
              ElementsAre("0", "250k", "500k", "750k", "1M", "1.25M", "1.5M"));
  EXPECT_THAT(Labels(CompactTics(151552)),
              ElementsAre("0", "25k", "50k", "75k", "100k", "125k", "150k"));
  EXPECT_THAT(Labels(CompactTics(10)), ElementsAre("0", "2", "4", "6", "8", "10"));
  EXPECT_THAT(Labels(CompactTics(7000)),
              ElementsAre("0", "1k", "2k", "3k", "4k", "5k", "6k", "7k"));
  EXPECT_EQ(CompactTics(250000)[1].at, 50000);
  EXPECT_TRUE(CompactTics(0).empty());
  EXPECT_TRUE(CompactTics(-5).empty());
}

TEST(LineChartFigureTest, WritesTicksWithTheirLabels) {
  LineChart chart = TwoPanels();
  chart.panels[0].x_tics = {{0, "0"}, {1000, "1k"}};
  chart.panels[0].y_tics = {{-1}, {1}};
  const std::string script = MustBuild(chart).script;
  EXPECT_THAT(script, HasSubstr("set xtics ('0' 0, '1k' 1000)\n"));
  EXPECT_THAT(script, HasSubstr("set ytics (-1, 1)\n"));
  EXPECT_THAT(script, HasSubstr("set xtics autofreq\n"));  // panel 1
}

TEST(LineChartFigureTest, RefusesBadCharts) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto code = [](const LineChart& chart) { return LineChartFigure(chart).status().code(); };
  const auto kBad = absl::StatusCode::kInvalidArgument;
  LineChart chart = TwoPanels();
  chart.name = "a/b";
  EXPECT_EQ(code(chart), kBad);
  EXPECT_EQ(code({.name = "empty"}), kBad);
  chart = TwoPanels();
  chart.columns = 0;
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panel_width = 100;
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].lines[0].y.pop_back();
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].lines[0].y_high.pop_back();
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].lines[0].y[0] = nan;
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].lines[0].x[1] = inf;
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].x_markers = {nan};
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[0].y_range = std::make_pair(1.0, 1.0);
  EXPECT_EQ(code(chart), kBad);
  chart = TwoPanels();
  chart.panels[1].x_range = std::make_pair(0.0, nan);
  EXPECT_EQ(code(chart), kBad);
}

}  // namespace
}  // namespace dcs::report
