// Copyright 2026 The DCS Authors.
//
// Renders each kind of chart with the real gnuplot (Debian's gnuplot-nox) and reads the images
// back: SVGs for their plot elements, legend and axis texts, PNGs and PDFs for their signature.
#include "services/cli/figure_render.h"

#include <filesystem>
#include <limits>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/bar_chart.h"
#include "report/heatmap_chart.h"
#include "report/line_chart.h"
#include "tests/testing/temp_dir.h"

namespace dcs::services::cli {
namespace {

using report::FigureFormat;
using report::GnuplotFigure;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsSupersetOf;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What an SVG from gnuplot holds: its plot elements (one <g id="gnuplot_plot_N"> per element
// of a plot command; in a multiplot "gnuplot_plot_Na" for the first panel, "..Nb" for the
// second, ...), counted over every panel, and the text of its <text> elements.
struct Svg {
  int plots = 0;
  std::vector<std::string> texts;
};

Svg ReadSvg(const std::string& text) {
  Svg svg;
  // An opaque legend draws the plots' groups twice (under and over its box): count ids once.
  const std::regex plot(R"re(<g id="(gnuplot_plot_\d+[a-z]*)")re");
  std::set<std::string> ids;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), plot);
       it != std::sregex_iterator(); ++it) {
    ids.insert((*it)[1].str());
  }
  svg.plots = static_cast<int>(ids.size());
  const std::regex text_element(R"(<text[^>]*>([^<]*)</text>)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), text_element);
       it != std::sregex_iterator(); ++it) {
    svg.texts.push_back((*it)[1].str());
  }
  return svg;
}

class FigureRenderTest : public dcs::testing::TempDirTest {
 protected:
  // Renders `figure` and returns the image's contents; fails the test on errors and warnings.
  std::string Render(const GnuplotFigure& figure, FigureFormat format = FigureFormat::kSvg) {
    absl::StatusOr<RenderedFigure> rendered = RenderFigure(figure, format, dir().string());
    EXPECT_TRUE(rendered.ok()) << rendered.status();
    if (!rendered.ok()) return "";
    EXPECT_EQ(rendered->path, Path(figure.ImageFileName(format)));
    EXPECT_EQ(rendered->gnuplot_output, "") << "gnuplot warned about " << figure.name;
    // The figure's data and script stay beside the image.
    EXPECT_TRUE(std::filesystem::is_regular_file(Path(figure.ScriptFileName())));
    for (const report::DataFile& data : figure.data) {
      EXPECT_TRUE(std::filesystem::is_regular_file(Path(data.name))) << data.name;
    }
    return ReadFile(rendered->path).value_or("");
  }
};

report::LineChart Curves() {
  return {.name = "curves",
          .title = "Learning curves",
          .panels = {{.title = "observe: none",
                      .x_label = "environment steps",
                      .y_label = "avg_combined",
                      .lines = {{.label = "sinusoidal",
                                 .x = {0, 1000, 2000},
                                 .y = {10, 60, 120},
                                 .y_low = {5, 40, 100},
                                 .y_high = {15, 80, 150}},
                                {.label = "static",
                                 .x = {0, 1000, 2000},
                                 .y = {10, 50, 90},
                                 .y_low = {8, 45, 80},
                                 .y_high = {12, 55, 95},
                                 .color = report::kBaselineColor,
                                 .dashed = true}}},
                     {.title = "observe: live",
                      .x_label = "environment steps",
                      .y_label = "avg_combined",
                      .lines = {{.label = "sinusoidal", .x = {0, 2000}, .y = {20, 130}}}}}};
}

TEST_F(FigureRenderTest, RendersLinesWithBandsToSvg) {
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(Curves());
  ASSERT_TRUE(figure.ok()) << figure.status();
  const std::string text = Render(*figure);
  EXPECT_TRUE(text.starts_with("<?xml")) << text.substr(0, 100);
  EXPECT_THAT(text, HasSubstr("<svg "));
  EXPECT_THAT(text, HasSubstr("</svg>"));
  const Svg svg = ReadSvg(text);
  EXPECT_EQ(svg.plots, 2 + 2 + 1);  // panel 0: two bands and two lines; panel 1: one line
  EXPECT_THAT(svg.texts, IsSupersetOf({"Learning curves", "observe: none", "observe: live",
                                       "environment steps", "avg_combined", "sinusoidal",
                                       "static"}));
  // The bands are translucent, the baseline dashed and black.
  EXPECT_THAT(text, HasSubstr("fill-opacity"));
  EXPECT_THAT(text, HasSubstr("stroke-dasharray"));
  EXPECT_THAT(text, HasSubstr("rgb(  0, 114, 178)"));  // #0072B2
}

TEST_F(FigureRenderTest, RendersPanelsWithMarkersAndSteps) {
  report::LineChart chart = Curves();
  chart.name = "markers";
  chart.panels[0].x_range = std::make_pair(0.0, 2000.0);
  chart.panels[0].y_range = std::make_pair(0.0, 200.0);
  chart.panels[0].x_markers = {1000};
  chart.panels[0].y_markers = {100};
  chart.panels[1].lines[0].steps = true;
  chart.panels.push_back({.title = "empty"});
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(chart);
  ASSERT_TRUE(figure.ok()) << figure.status();
  const Svg svg = ReadSvg(Render(*figure));
  EXPECT_EQ(svg.plots, 4 + 1 + 1);  // the empty panel plots NaN
  EXPECT_THAT(svg.texts, IsSupersetOf({"empty", "no data"}));
}

TEST_F(FigureRenderTest, RendersGroupedBars) {
  const report::BarChart chart{
      .name = "bars",
      .title = "Per context",
      .panels = {
          {.title = "observe: none",
           .x_label = "evaluation context",
           .y_label = "mean return",
           .categories = {{"0.1", "OOD-low"}, {"0.4", "ID"}, {"0.6", "ID"}, {"0.9", "OOD-high"}},
           .series = {{.label = "sinusoidal",
                       .y = {10, 200, 180, kNaN},
                       .y_low = {5, 150, 170, kNaN},
                       .y_high = {20, 250, 190, kNaN}},
                      {.label = "static", .y = {-20, 150, 160, 40}, .color = "#000000"}}}}};
  absl::StatusOr<GnuplotFigure> figure = report::BarChartFigure(chart);
  ASSERT_TRUE(figure.ok()) << figure.status();
  const Svg svg = ReadSvg(Render(*figure));
  EXPECT_EQ(svg.plots, 2 + 1);  // two series of bars, one of error bars
  EXPECT_THAT(svg.texts, IsSupersetOf({"Per context", "evaluation context", "mean return",
                                       "OOD-low", "ID", "OOD-high", "0.1", "0.9", "sinusoidal",
                                       "static"}));
}

TEST_F(FigureRenderTest, RendersAHeatmapWithItsNumbers) {
  const report::Heatmap heatmap{.name = "heatmap",
                                .title = "Relative to static",
                                .x_label = "observe mode",
                                .y_label = "schedule family",
                                .column_labels = {"none", "initial", "live"},
                                .row_labels = {"sinusoidal", "random_walk"},
                                .values = {{12.3, -40, 0}, {kNaN, 3, 25}},
                                .value_label = "difference"};
  absl::StatusOr<GnuplotFigure> figure = report::HeatmapFigure(heatmap);
  ASSERT_TRUE(figure.ok()) << figure.status();
  const Svg svg = ReadSvg(Render(*figure));
  EXPECT_EQ(svg.plots, 3);  // grey cells, coloured cells, numbers
  EXPECT_THAT(svg.texts, IsSupersetOf({"Relative to static", "observe mode", "schedule family",
                                       "difference", "none", "live", "sinusoidal", "random_walk",
                                       "+12.3", "-40.0", "+0.0", "n/a", "+25.0"}));
}

TEST_F(FigureRenderTest, DrawsTitlesAndLabelsLiterally) {
  report::LineChart chart = Curves();
  chart.title = R"(it's "quoted" \n x_1 y^2 @ & <b>)";
  chart.panels[0].lines[0].label = "a_b, c";
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(chart);
  ASSERT_TRUE(figure.ok()) << figure.status();
  const Svg svg = ReadSvg(Render(*figure));
  EXPECT_THAT(svg.texts, Contains(R"(it's "quoted" \n x_1 y^2 @ &amp; &lt;b>)"));
  EXPECT_THAT(svg.texts, Contains("a_b, c"));
}

TEST_F(FigureRenderTest, RendersPngAndPdf) {
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(Curves());
  ASSERT_TRUE(figure.ok()) << figure.status();
  const std::string png = Render(*figure, FigureFormat::kPng);
  EXPECT_TRUE(png.starts_with("\x89PNG\r\n\x1a\n"));
  EXPECT_GT(png.size(), 10000u);
  const std::string pdf = Render(*figure, FigureFormat::kPdf);
  EXPECT_TRUE(pdf.starts_with("%PDF-"));
}

TEST_F(FigureRenderTest, MissingGnuplotIsAFailedPreconditionThatLeavesTheFiles) {
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(Curves());
  ASSERT_TRUE(figure.ok()) << figure.status();
  for (const std::string gnuplot : {"/nonexistent/gnuplot", "no-such-gnuplot-program"}) {
    const absl::StatusOr<RenderedFigure> rendered =
        RenderFigure(*figure, FigureFormat::kSvg, dir().string(), {.gnuplot = gnuplot});
    EXPECT_EQ(rendered.status().code(), absl::StatusCode::kFailedPrecondition);
    EXPECT_THAT(rendered.status().message(), HasSubstr("curves.gp"));
    EXPECT_THAT(rendered.status().message(), HasSubstr("gnuplot-nox"));
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(Path("curves.gp")));
  EXPECT_TRUE(std::filesystem::is_regular_file(Path("curves.csv")));
  EXPECT_FALSE(std::filesystem::exists(Path("curves.svg")));
}

TEST_F(FigureRenderTest, AGnuplotErrorNamesTheScriptAndQuotesGnuplot) {
  const GnuplotFigure figure{.name = "broken",
                             .script = "set output 'broken.svg'\nplot 'missing.csv' using 1:2\n"};
  const absl::StatusOr<RenderedFigure> rendered =
      RenderFigure(figure, FigureFormat::kSvg, dir().string());
  EXPECT_EQ(rendered.status().code(), absl::StatusCode::kInternal);
  EXPECT_THAT(rendered.status().message(), HasSubstr("broken.gp"));
  EXPECT_THAT(rendered.status().message(), HasSubstr("exited with status 1"));
  EXPECT_THAT(rendered.status().message(), HasSubstr("missing.csv"));  // gnuplot's words
  // gnuplot's output is not left behind.
  EXPECT_FALSE(std::filesystem::exists(Path(".broken.gnuplot-output")));
}

TEST_F(FigureRenderTest, AScriptThatWritesNoImageIsAnError) {
  const GnuplotFigure figure{.name = "silent", .script = "print 'nothing to draw'\n"};
  const absl::StatusOr<RenderedFigure> rendered =
      RenderFigure(figure, FigureFormat::kSvg, dir().string());
  EXPECT_EQ(rendered.status().code(), absl::StatusCode::kInternal);
  EXPECT_THAT(rendered.status().message(), HasSubstr("silent.svg"));
  EXPECT_THAT(rendered.status().message(), HasSubstr("nothing to draw"));
}

TEST_F(FigureRenderTest, AnUnknownFormatStopsTheScript) {
  // A figure's own script refuses a format it does not know (run by hand with -e).
  absl::StatusOr<GnuplotFigure> figure = report::LineChartFigure(Curves());
  ASSERT_TRUE(figure.ok()) << figure.status();
  figure->script.insert(0, "format = 'jpeg'\n");
  const absl::StatusOr<RenderedFigure> rendered =
      RenderFigure(*figure, FigureFormat::kSvg, dir().string());
  EXPECT_EQ(rendered.status().code(), absl::StatusCode::kInternal);
  EXPECT_THAT(rendered.status().message(), HasSubstr("unknown format jpeg"));
}

TEST_F(FigureRenderTest, AHungGnuplotIsKilledAtTheTimeout) {
  const GnuplotFigure figure{.name = "slow", .script = "pause 30\n"};
  const absl::StatusOr<RenderedFigure> rendered = RenderFigure(
      figure, FigureFormat::kSvg, dir().string(), {.timeout = absl::Milliseconds(300)});
  EXPECT_EQ(rendered.status().code(), absl::StatusCode::kDeadlineExceeded);
  EXPECT_THAT(rendered.status().message(), HasSubstr("slow.gp"));
}

TEST_F(FigureRenderTest, RefusesFileNamesOutsideTheDirectory) {
  const GnuplotFigure figure{.name = "escape", .data = {{.name = "../outside.csv"}}};
  EXPECT_EQ(WriteFigureFiles(figure, dir().string()).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(WriteFigureFiles({.name = "../up"}, dir().string()).code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::services::cli
