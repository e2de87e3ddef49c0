// Copyright 2026 The DCS Authors.
#include "coordinator/line_plot.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;
using ::testing::Not;

// Occurrences of `needle` in `haystack`.
int Count(absl::string_view haystack, absl::string_view needle) {
  int count = 0;
  for (size_t at = haystack.find(needle); at != absl::string_view::npos;
       at = haystack.find(needle, at + needle.size())) {
    ++count;
  }
  return count;
}

std::string Render(const Figure& figure) {
  absl::StatusOr<std::string> svg = RenderSvg(figure);
  EXPECT_TRUE(svg.ok()) << svg.status();
  return svg.ok() ? *svg : "";
}

Series Line(std::string label, std::vector<double> x, std::vector<double> y) {
  return {.label = std::move(label), .x = std::move(x), .y = std::move(y)};
}

// A series of `n` points of a sinusoid over x = 0..n-1, in [-1, 1].
Series Sinusoid(std::string label, int n, double periods, double phase) {
  Series s{.label = std::move(label)};
  for (int i = 0; i < n; ++i) {
    s.x.push_back(i);
    s.y.push_back(std::sin(2 * M_PI * periods * i / (n - 1) + phase));
  }
  return s;
}

struct Rect {
  double x, y, width, height;
};

// The plot-area rectangles, in panel order.
std::vector<Rect> PlotAreas(const std::string& svg) {
  static const std::regex kRect(R"re(<rect class="plot-area" x="([-0-9.]+)" y="([-0-9.]+)")re"
                                R"re( width="([-0-9.]+)" height="([-0-9.]+)")re");
  std::vector<Rect> rects;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), kRect); it != std::sregex_iterator();
       ++it) {
    rects.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3]),
                     std::stod((*it)[4])});
  }
  return rects;
}

// The points of every polyline, in order.
std::vector<std::vector<std::pair<double, double>>> Polylines(const std::string& svg) {
  static const std::regex kPolyline(R"re(<polyline class="series" points="([^"]*)")re");
  std::vector<std::vector<std::pair<double, double>>> lines;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), kPolyline);
       it != std::sregex_iterator(); ++it) {
    std::vector<std::pair<double, double>> points;
    for (absl::string_view point : absl::StrSplit((*it)[1].str(), ' ', absl::SkipEmpty())) {
      std::vector<absl::string_view> xy = absl::StrSplit(point, ',');
      EXPECT_EQ(xy.size(), 2u) << point;
      double x = 0;
      double y = 0;
      EXPECT_TRUE(absl::SimpleAtod(xy[0], &x) && absl::SimpleAtod(xy[1], &y)) << point;
      points.emplace_back(x, y);
    }
    lines.push_back(std::move(points));
  }
  return lines;
}

// The text of the tick labels of axis `axis` ("x" or "y"), in document order.
std::vector<std::string> TickLabels(const std::string& svg, const std::string& axis) {
  const std::regex label("class=\"tick-label " + axis + "\">([^<]*)</text>");
  std::vector<std::string> labels;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator();
       ++it) {
    labels.push_back((*it)[1]);
  }
  return labels;
}

TEST(RenderSvgTest, IsAStandaloneSvgDocument) {
  const std::string svg = Render({.title = "Trajectories",
                                  .panels = {{.title = "linear",
                                              .series = {Line("a", {0, 1, 2}, {0, 1, 0})}}}});
  absl::string_view body = svg;
  if (absl::StartsWith(body, "<?xml")) body.remove_prefix(body.find("?>") + 2);
  body = absl::StripAsciiWhitespace(body);
  EXPECT_TRUE(absl::StartsWith(body, "<svg ")) << svg;
  EXPECT_TRUE(absl::EndsWith(body, "</svg>")) << svg;
  EXPECT_THAT(svg, HasSubstr("xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_EQ(Count(svg, "<svg"), 1);
  EXPECT_EQ(Count(svg, "</svg>"), 1);
  // Every opened group is closed.
  EXPECT_EQ(Count(svg, "<g "), Count(svg, "</g>"));
  EXPECT_EQ(Count(svg, "<text "), Count(svg, "</text>"));
}

TEST(RenderSvgTest, DrawsOnePanelGroupPerPanelAndOnePolylinePerSeries) {
  Figure figure{.title = "Schedules", .columns = 2};
  for (int p = 0; p < 5; ++p) {
    Panel panel{.title = "family " + std::to_string(p)};
    for (int s = 0; s < p; ++s) panel.series.push_back(Sinusoid("run", 20, 1, s));
    figure.panels.push_back(std::move(panel));
  }
  const std::string svg = Render(figure);
  EXPECT_EQ(Count(svg, "class=\"panel\""), 5);
  for (int p = 0; p < 5; ++p) EXPECT_THAT(svg, HasSubstr("id=\"panel-" + std::to_string(p) + "\""));
  EXPECT_EQ(Count(svg, "<polyline"), 0 + 1 + 2 + 3 + 4);
  EXPECT_EQ(PlotAreas(svg).size(), 5u);
  // Two columns of 360 px and three rows of 220 px, plus margins and the title band.
  EXPECT_THAT(svg, HasSubstr("width=\"736\" height=\"704\""));
}

TEST(RenderSvgTest, FigureIsOnlyAsWideAsItsPanels) {
  const std::string svg = Render({.panels = {{.title = "only"}}, .columns = 3});
  EXPECT_THAT(svg, HasSubstr("width=\"376\""));
}

TEST(RenderSvgTest, EscapesText) {
  const std::string nasty = "a <&> \"b\" 'c'";
  const std::string escaped = "a &lt;&amp;&gt; &quot;b&quot; &apos;c&apos;";
  const std::string svg = Render({.title = nasty,
                                  .panels = {{.title = nasty,
                                              .x_label = nasty,
                                              .y_label = nasty,
                                              .series = {Line(nasty, {0, 1}, {0, 1})}}}});
  EXPECT_THAT(svg, Not(HasSubstr("<&>")));
  EXPECT_THAT(svg, Not(HasSubstr("'c'")));
  // Figure title (twice: <title> and the text), panel title, two axis labels, legend, tooltip.
  EXPECT_EQ(Count(svg, escaped), 7) << svg;
}

TEST(RenderSvgTest, ReplacesControlCharacters) {
  const std::string svg = Render({.title = std::string("a\x01" "b\nc")});
  EXPECT_THAT(svg, HasSubstr(">a b c</text>"));
}

TEST(RenderSvgTest, EllipsizesTextTooWideForItsPanel) {
  const std::string long_title(200, 'w');
  const std::string svg = Render({.panels = {{.title = long_title}}});
  EXPECT_THAT(svg, Not(HasSubstr(long_title)));
  EXPECT_THAT(svg, HasSubstr("w\xE2\x80\xA6</text>"));
}

TEST(RenderSvgTest, HonoursAFixedYRange) {
  const std::string svg = Render(
      {.panels = {{.series = {Line("", {0, 1, 2, 3}, {-1, 1, 0.5, -1})},
                   .y_range = std::make_pair(-1.0, 1.0)}}});
  const std::vector<Rect> areas = PlotAreas(svg);
  ASSERT_EQ(areas.size(), 1u);
  const Rect& area = areas[0];
  const auto lines = Polylines(svg);
  ASSERT_EQ(lines.size(), 1u);
  ASSERT_EQ(lines[0].size(), 4u);
  const double bottom = area.y + area.height;
  EXPECT_NEAR(lines[0][0].second, bottom, 0.051);
  EXPECT_NEAR(lines[0][1].second, area.y, 0.051);
  EXPECT_NEAR(lines[0][2].second, area.y + area.height / 4, 0.051);
  EXPECT_NEAR(lines[0][3].second, bottom, 0.051);
  // The x axis spans the data exactly.
  EXPECT_NEAR(lines[0][0].first, area.x, 0.051);
  EXPECT_NEAR(lines[0][3].first, area.x + area.width, 0.051);
  EXPECT_THAT(TickLabels(svg, "y"), ElementsAre("-1", "-0.5", "0", "0.5", "1"));
}

TEST(RenderSvgTest, ClipsLinesLeavingAFixedRange) {
  const std::string svg = Render({.panels = {{.series = {Line("", {0, 1}, {0, 1e300})},
                                              .y_range = std::make_pair(0.0, 1.0)}}});
  EXPECT_THAT(svg, HasSubstr("clip-path=\"url(#dcs-clip-0)\""));
  const auto lines = Polylines(svg);
  ASSERT_EQ(lines.size(), 1u);
  // Far-away points are clamped rather than written with 300 digits.
  EXPECT_LT(svg.size(), 20000u);
}

TEST(RenderSvgTest, LeavesAMarginAroundDataWithoutAFixedRange) {
  const std::string svg = Render({.panels = {{.series = {Line("", {0, 1}, {-1, 1})}}}});
  const Rect area = PlotAreas(svg).at(0);
  const auto lines = Polylines(svg);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_GT(lines[0][0].second, area.y + area.height * 0.9);
  EXPECT_LT(lines[0][0].second, area.y + area.height - 1);
  EXPECT_LT(lines[0][1].second, area.y + area.height * 0.1);
  EXPECT_GT(lines[0][1].second, area.y + 1);
}

TEST(RenderSvgTest, TickLabelsOfA0To500AxisInclude0And500) {
  const std::string svg = Render({.panels = {{.series = {Sinusoid("", 501, 2, 0)},
                                              .y_range = std::make_pair(-1.0, 1.0)}}});
  const std::vector<std::string> labels = TickLabels(svg, "x");
  EXPECT_THAT(labels, Contains("0"));
  EXPECT_THAT(labels, Contains("500"));
  EXPECT_GE(labels.size(), 4u);
  EXPECT_LE(labels.size(), 6u);
}

TEST(RenderSvgTest, PicksNiceTicksForAssortedRanges) {
  struct Case {
    std::pair<double, double> range;
    std::vector<std::string> labels;
  };
  const std::vector<Case> cases = {
      {{0, 499}, {"0", "100", "200", "300", "400"}},
      {{0, 1}, {"0", "0.2", "0.4", "0.6", "0.8", "1"}},
      {{0, 14}, {"0", "2.5", "5", "7.5", "10", "12.5"}},
      {{0, 2e6}, {"0", "0.5M", "1M", "1.5M", "2M"}},
      {{0, 50000}, {"0", "10k", "20k", "30k", "40k", "50k"}},
      {{-0.003, 0.003}, {"-0.002", "0", "0.002"}},
  };
  for (const Case& c : cases) {
    const std::string svg = Render({.panels = {{.x_range = c.range}}});
    const std::vector<std::string> labels = TickLabels(svg, "x");
    // {-0.003, 0.003} has no 4-to-6-tick step; 3 and 7 are as close, and fewer is clearer.
    EXPECT_THAT(labels, ElementsAreArray(c.labels)) << c.range.first << ".." << c.range.second;
  }
}

TEST(RenderSvgTest, ThinsTicksThatWouldCrowdASmallPanel) {
  const std::string svg = Render({.panels = {{.title = "small",
                                              .x_label = "steps",
                                              .series = {Line("a", {0, 1}, {0, 1})},
                                              .y_range = std::make_pair(0.0, 1.0),
                                              .x_range = std::make_pair(0.0, 2e6)}},
                                  .panel_width = 120,
                                  .panel_height = 100});
  const Rect area = PlotAreas(svg).at(0);
  const std::vector<std::string> x_labels = TickLabels(svg, "x");
  const std::vector<std::string> y_labels = TickLabels(svg, "y");
  ASSERT_GE(x_labels.size(), 2u);
  ASSERT_GE(y_labels.size(), 2u);
  EXPECT_GE(area.height / (y_labels.size() - 1), 18) << svg;
  EXPECT_GE(area.width / (x_labels.size() - 1), 30) << svg;  // "0.5M" is about 25 px wide
}

TEST(RenderSvgTest, DrawsMarkersInsideTheAxisRange) {
  Panel panel{.series = {Line("", {0, 100}, {0, 1})},
              .y_range = std::make_pair(-1.5, 1.5),
              .x_range = std::make_pair(0.0, 100.0)};
  panel.x_markers = {25, 50, 150};  // 150 is outside the x range
  panel.y_markers = {-1, 0, 1};
  const std::string svg = Render({.panels = {panel}});
  const Rect area = PlotAreas(svg).at(0);
  const std::regex x_marker(R"re(<path class="x-marker" d="([^"]*)")re");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(svg, match, x_marker)) << svg;
  EXPECT_EQ(Count(match[1].str(), "M"), 2);
  const std::regex y_marker(R"re(<path class="y-marker" d="([^"]*)")re");
  ASSERT_TRUE(std::regex_search(svg, match, y_marker)) << svg;
  EXPECT_EQ(Count(match[1].str(), "M"), 3);
  // The 50 marker is in the middle of the plot area.
  char middle[32];
  std::snprintf(middle, sizeof(middle), "M%g ", area.x + area.width / 2);
  EXPECT_THAT(svg, HasSubstr(middle));
}

TEST(RenderSvgTest, RejectsNonFiniteMarkers) {
  Panel panel;
  panel.x_markers = {std::numeric_limits<double>::infinity()};
  EXPECT_EQ(RenderSvg({.panels = {panel}}).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(RenderSvgTest, RejectsSeriesOfMismatchedLengths) {
  absl::StatusOr<std::string> svg =
      RenderSvg({.panels = {{.series = {Line("bad", {0, 1, 2}, {0, 1})}}}});
  EXPECT_EQ(svg.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(svg.status().message(), HasSubstr("bad"));
}

TEST(RenderSvgTest, RejectsNaNAndInfinity) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Series& s : {Line("", {0, 1}, {0, nan}), Line("", {nan, 1}, {0, 1}),
                          Line("", {0, 1}, {0, inf}), Line("", {0, -inf}, {0, 1})}) {
    EXPECT_EQ(RenderSvg({.panels = {{.series = {s}}}}).status().code(),
              absl::StatusCode::kInvalidArgument);
  }
  EXPECT_EQ(RenderSvg({.panels = {{.y_range = std::make_pair(0.0, nan)}}}).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(RenderSvg({.panels = {{.x_range = std::make_pair(-inf, 0.0)}}}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(RenderSvgTest, RejectsBadLayoutAndRanges) {
  EXPECT_EQ(RenderSvg({.columns = 0}).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(RenderSvg({.panel_width = 10}).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(RenderSvg({.panels = {{.y_range = std::make_pair(1.0, 1.0)}}}).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(RenderSvg({.panels = {{.x_range = std::make_pair(2.0, 1.0)}}}).status().code(),
            absl::StatusCode::kInvalidArgument);
  const double max = std::numeric_limits<double>::max();
  EXPECT_EQ(RenderSvg({.panels = {{.series = {Line("", {0, 1}, {-max, max})}}}}).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(RenderSvgTest, DegenerateDataRendersWithoutNaNOrInfinity) {
  Figure figure{.title = "Degenerate"};
  figure.panels.push_back({.title = "constant", .series = {Line("c", {0, 1, 2}, {3, 3, 3})}});
  figure.panels.push_back({.title = "zero", .series = {Line("z", {5, 5}, {0, 0})}});
  figure.panels.push_back({.title = "one point", .series = {Line("p", {7}, {-2})}});
  figure.panels.push_back({.title = "empty series", .series = {Line("e", {}, {})}});
  figure.panels.push_back({.title = "no series"});
  figure.panels.push_back({.title = "tiny", .series = {Line("t", {0, 1}, {1e-300, 2e-300})}});
  figure.panels.push_back({.title = "huge", .series = {Line("h", {0, 1}, {1e300, 1e300})}});
  const std::string svg = absl::AsciiStrToLower(Render(figure));
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));
  EXPECT_EQ(Count(svg, "<polyline"), 6);
  EXPECT_EQ(Count(svg, "<circle"), 1);  // the single point is drawn as a dot
  for (const auto& line : Polylines(svg)) {
    for (const auto& [x, y] : line) {
      EXPECT_TRUE(std::isfinite(x) && std::isfinite(y));
    }
  }
  // The constant series sits in the middle of its panel.
  const Rect area = PlotAreas(svg).at(0);
  EXPECT_NEAR(Polylines(svg).at(0).at(0).second, area.y + area.height / 2, 0.051);
}

TEST(RenderSvgTest, WritesLongSeriesAsOnePolylineRoundedToATenthOfAPixel) {
  Panel panel{.title = "long", .y_range = std::make_pair(-1.0, 1.0)};
  for (int s = 0; s < 3; ++s) panel.series.push_back(Sinusoid("s", 500, 3, s));
  const std::string svg = Render({.panels = {panel}});
  const auto lines = Polylines(svg);
  ASSERT_EQ(lines.size(), 3u);
  for (const auto& line : lines) EXPECT_EQ(line.size(), 500u);
  static const std::regex kTooPrecise(R"re(points="[^"]*\.[0-9][0-9])re");
  EXPECT_FALSE(std::regex_search(svg, kTooPrecise));
}

TEST(RenderSvgTest, DrawsALegendOnlyForLabelledSeries) {
  const std::string with = Render(
      {.panels = {{.series = {Line("alpha", {0, 1}, {0, 1}), Line("", {0, 1}, {1, 0})}}}});
  EXPECT_EQ(Count(with, "class=\"legend\""), 1);
  EXPECT_THAT(with, HasSubstr(">alpha</text>"));
  const std::string without =
      Render({.panels = {{.series = {Line("", {0, 1}, {0, 1})}}}});
  EXPECT_EQ(Count(without, "class=\"legend\""), 0);
}

TEST(RenderSvgTest, SummarisesALegendTooLongForThePanel) {
  Panel panel;
  for (int s = 0; s < 40; ++s) {
    panel.series.push_back(Line("series number " + std::to_string(s), {0, 1}, {0, 1}));
  }
  const std::string svg = Render({.panels = {panel}});
  EXPECT_THAT(svg, HasSubstr(" more</text>"));
  EXPECT_THAT(svg, Not(HasSubstr(">series number 39</text>")));
  // The plot keeps a good part of the panel.
  EXPECT_GE(PlotAreas(svg).at(0).height, 0.35 * 220);
}

TEST(RenderSvgTest, SeriesKeepTheirColourAcrossPanels) {
  const Panel panel{.series = {Line("a", {0, 1}, {0, 1}), Line("b", {0, 1}, {1, 0})}};
  const std::string svg = Render({.panels = {panel, panel}});
  static const std::regex kStroke(R"re(<polyline[^>]*stroke="(#[0-9A-Fa-f]{6})")re");
  std::vector<std::string> colours;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), kStroke);
       it != std::sregex_iterator(); ++it) {
    colours.push_back((*it)[1]);
  }
  ASSERT_EQ(colours.size(), 4u);
  EXPECT_NE(colours[0], colours[1]);
  EXPECT_EQ(colours[0], colours[2]);
  EXPECT_EQ(colours[1], colours[3]);
}

}  // namespace
}  // namespace dcs::coordinator
