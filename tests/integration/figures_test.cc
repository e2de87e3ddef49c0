// Copyright 2026 The DCS Authors.
//
// Figures as a person sees them: a sweep's figures rendered by the real gnuplot, their
// index.html opened in headless Chromium (Debian's), which reports whether every image loaded
// and takes a screenshot; and `dcs schedule preview --svg`. The rendered files are left in the
// test's temporary directory (printed) to be looked at.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/sweep_figures.h"
#include "report/sweep_index_html.h"
#include "report/sweep_report.h"
#include "services/cli/figure_render.h"
#include "tests/integration/browser.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using report::FigureFormat;
using report::GnuplotFigure;
using ::testing::HasSubstr;

// Deterministic noise in [0, 1).
double Noise(double a, double b) {
  const double x = std::sin(a * 12.9898 + b * 78.233) * 43758.5453;
  return x - std::floor(x);
}

// A CartPole-like sweep: five conditions (static first) in three observe modes, five seeds,
// an evaluation every 10k steps up to 150k, contexts in three splits.
v1::SweepResults DemoResults() {
  struct Condition {
    const char* name;
    const char* family;
    double quality;
  };
  const Condition conditions[] = {{"static", "static", 0.7},
                                  {"sinusoidal_small", "sinusoidal", 0.8},
                                  {"sinusoidal_large", "sinusoidal", 0.9},
                                  {"random_walk", "random_walk", 0.75},
                                  {"sudden_jump", "sudden_jump", 0.6}};
  const std::pair<v1::Split, std::vector<double>> splits[] = {
      {v1::SPLIT_OOD_LOW, {0.1, 0.2, 0.3}},
      {v1::SPLIT_ID, {0.35, 0.45, 0.55, 0.65, 0.75}},
      {v1::SPLIT_OOD_HIGH, {0.9, 1.1, 1.3}}};
  v1::SweepResults results;
  results.set_sweep_id("sweep-3");
  results.set_name("cartpole_length");
  results.set_seeds(5);
  int mode_index = 0;
  for (const char* mode : {"none", "initial", "live"}) {
    ++mode_index;
    int condition_index = 0;
    for (const Condition& condition : conditions) {
      ++condition_index;
      v1::TrialResults& trial = *results.add_trials();
      trial.set_condition(condition.name);
      trial.set_family(condition.family);
      trial.set_observe(mode);
      const double quality = condition.quality + 0.03 * mode_index;
      for (int seed = 0; seed < 5; ++seed) {
        v1::EvaluationLog& log = *trial.add_runs();
        log.set_seed(seed);
        for (int step = 0; step <= 150000; step += 10000) {
          v1::Evaluation& evaluation = *log.add_evaluations();
          evaluation.set_step(step);
          const double noise = Noise(seed + 10 * condition_index + 100 * mode_index, step);
          evaluation.set_avg_combined(
              std::min(500.0, 500 * quality * (1 - std::exp(-step / 40000.0)) + 40 * noise));
        }
        v1::Evaluation& last = *log.mutable_evaluations()->rbegin();
        for (const auto& [split, values] : splits) {
          for (const double value : values) {
            v1::ContextEvaluation& context = *last.add_contexts();
            context.set_split(split);
            context.set_value(value);
            const double distance = value < 0.35 ? 0.35 - value : value > 0.75 ? value - 0.75 : 0;
            context.set_mean(last.avg_combined() * std::exp(-3 * distance) *
                             (0.9 + 0.2 * Noise(seed, value)));
          }
        }
        log.set_last(last.avg_combined());
        log.set_complete(true);
        // Coverage as the paper's: about 6.5 % of the cells in the first 50k steps, few after.
        v1::ProjectionCoverage& coverage = *log.add_coverage();
        coverage.set_projection("state");
        coverage.set_cells(20736);
        for (const auto& [start, visited, added] :
             {std::tuple(0, 1300 + 40 * condition_index + 10 * seed, 1300), std::tuple(50000, 130, 5),
              std::tuple(100000, 60, 1)}) {
          v1::CoverageWindow& window = *coverage.add_windows();
          window.set_start_step(start);
          window.set_end_step(start + 50000);
          window.set_visited(visited);
          window.set_new_cells(start == 0 ? visited : added);
        }
      }
    }
  }
  return results;
}

constexpr char kTable[] =
    "<table><caption>cartpole_length: IQM [Q1, Q3] of avg_combined</caption>"
    "<thead><tr><th>condition</th><th>none</th></tr></thead>"
    "<tbody><tr><td>static</td><td>350.1 [340.2, 360.3]</td></tr></tbody></table>";

class FiguresTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_FALSE(ChromiumPath().empty())
        << "headless Chromium is needed: apt-get install chromium";
    dir_ = dcs::testing::MakeTempDir();
    std::cout << "figures in " << dir_ << std::endl;
  }

  // Renders every figure of DemoResults() as `format` and writes index.html.
  std::vector<GnuplotFigure> RenderReport(FigureFormat format) {
    const v1::SweepResults results = DemoResults();
    report::ReportOptions options;
    options.bootstrap_resamples = 200;
    const absl::StatusOr<v1::SweepReport> report = report::BuildSweepReport(results, options);
    EXPECT_TRUE(report.ok()) << report.status();
    if (!report.ok()) return {};
    absl::StatusOr<std::vector<GnuplotFigure>> figures = report::SweepFigures(results, *report);
    EXPECT_TRUE(figures.ok()) << figures.status();
    if (!figures.ok()) return {};
    for (const GnuplotFigure& figure : *figures) {
      absl::StatusOr<services::cli::RenderedFigure> rendered =
          services::cli::RenderFigure(figure, format, dir_);
      EXPECT_TRUE(rendered.ok()) << rendered.status();
      if (rendered.ok()) {
        EXPECT_EQ(rendered->gnuplot_output, "") << figure.name;
      }
    }
    EXPECT_TRUE(WriteFileAtomically(
                    dir_ + "/index.html",
                    report::SweepIndexHtml("Sweep cartpole_length", kTable, *figures, format))
                    .ok());
    return *figures;
  }

  std::string dir_;
};

TEST_F(FiguresTest, EveryFigureOfTheReportLoadsInABrowser) {
  const std::vector<GnuplotFigure> figures = RenderReport(FigureFormat::kSvg);
  ASSERT_EQ(figures.size(), 5u);  // the coverage figure last
  const std::vector<std::string> images = LoadedImages(dir_ + "/index.html");
  ASSERT_EQ(images.size(), figures.size());
  for (size_t i = 0; i < images.size(); ++i) {
    const std::vector<std::string> fields = absl::StrSplit(images[i], ' ');
    ASSERT_EQ(fields.size(), 3u) << images[i];
    EXPECT_EQ(fields[0], figures[i].ImageFileName(FigureFormat::kSvg));
    EXPECT_EQ(fields[1], "loaded") << images[i];
    // At the figure's own size (an SVG without one would shrink to 300 x 150 in an <img>).
    int width = 0;
    int height = 0;
    ASSERT_EQ(std::sscanf(fields[2].c_str(), "%dx%d", &width, &height), 2) << images[i];
    EXPECT_GE(width, 600) << images[i];
    EXPECT_GE(height, 200) << images[i];
  }
}

TEST_F(FiguresTest, TheImageCheckSeesAMissingImage) {
  RenderReport(FigureFormat::kPng);
  fs::remove(dir_ + "/family_heatmap.png");
  const std::vector<std::string> images = LoadedImages(dir_ + "/index.html");
  ASSERT_EQ(images.size(), 5u);
  EXPECT_THAT(images[0], HasSubstr("learning_curves.png loaded"));
  EXPECT_EQ(images[2], "family_heatmap.png broken 0x0");
}

TEST_F(FiguresTest, TheReportPageShowsTheTableAndTheFigures) {
  RenderReport(FigureFormat::kSvg);
  const Screenshot image =
      TakeScreenshot(dir_ + "/index.html", dir_ + "/index.png", 1400, 2400);
  EXPECT_EQ(image.width, 1400);
  EXPECT_EQ(image.height, 2400);
  // Not a blank page: many pixels are drawn, in many colours, the Okabe-Ito blue among them.
  int drawn = 0;
  int blue = 0;
  std::set<int> colours;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const int r = image.rgb[i], g = image.rgb[i + 1], b = image.rgb[i + 2];
    if (r < 235 || g < 235 || b < 235) ++drawn;
    if (std::abs(r - 0) < 30 && std::abs(g - 114) < 30 && std::abs(b - 178) < 30) ++blue;
    colours.insert((r << 16) | (g << 8) | b);
  }
  const int pixels = image.width * image.height;
  EXPECT_GT(drawn, pixels / 20) << "drawn pixels: " << drawn << " of " << pixels;
  EXPECT_GT(blue, 1000);
  EXPECT_GT(colours.size(), 200u);
}

TEST_F(FiguresTest, SchedulePreviewDrawsItsFigureWithGnuplot) {
  const RunResult preview =
      RunProgram(BinaryPath("dcs"), {"schedule", "preview", "--spec", "sinusoidal", "--out",
                                     dir_ + "/traj.csv", "--svg", dir_ + "/preview.svg"});
  ASSERT_EQ(preview.exit_code, 0) << preview.output;
  EXPECT_THAT(preview.output, HasSubstr("wrote the figure to " + dir_ + "/preview.svg"));
  const std::string svg = ReadFile(dir_ + "/preview.svg").value_or("");
  EXPECT_THAT(svg, HasSubstr("<svg"));
  EXPECT_THAT(svg, HasSubstr("<text>amplitude_frac 0.5, period 125</text>"));
  EXPECT_THAT(svg, HasSubstr("<text>normalised context</text>"));
  EXPECT_THAT(svg, HasSubstr("<text>step</text>"));
  // The script and the data stay beside it, and render the same figure again.
  EXPECT_TRUE(fs::is_regular_file(dir_ + "/preview.gp"));
  EXPECT_THAT(ReadFile(dir_ + "/preview.csv").value_or(""),
              HasSubstr("panel,line,x,y,panel_title,label\n0,0,0,"));
  fs::remove(dir_ + "/preview.svg");
  const RunResult by_hand = RunProgram("/bin/sh", {"-c", "cd " + dir_ + " && gnuplot preview.gp"});
  EXPECT_EQ(by_hand.exit_code, 0) << by_hand.output;
  EXPECT_TRUE(fs::is_regular_file(dir_ + "/preview.svg"));
}

TEST_F(FiguresTest, SchedulePreviewRefusesAFigureWhoseDataWouldOverwriteTheCsv) {
  const RunResult preview =
      RunProgram(BinaryPath("dcs"), {"schedule", "preview", "--spec", "sinusoidal", "--out",
                                     dir_ + "/traj.csv", "--svg", dir_ + "/traj.svg"});
  EXPECT_NE(preview.exit_code, 0);
  EXPECT_THAT(preview.output, HasSubstr("which is the --out file"));
  EXPECT_FALSE(fs::exists(dir_ + "/traj.csv"));
}

}  // namespace
}  // namespace dcs::integration
