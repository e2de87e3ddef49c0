// Copyright 2026 The DCS Authors.
#include "report/gnuplot_figure.h"

#include <cmath>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;

TEST(GnuplotFigureTest, NamesItsScriptAndImages) {
  const GnuplotFigure figure{.name = "learning_curves"};
  EXPECT_EQ(figure.ScriptFileName(), "learning_curves.gp");
  EXPECT_EQ(figure.ImageFileName(FigureFormat::kSvg), "learning_curves.svg");
  EXPECT_EQ(figure.ImageFileName(FigureFormat::kPng), "learning_curves.png");
  EXPECT_EQ(figure.ImageFileName(FigureFormat::kPdf), "learning_curves.pdf");
}

TEST(CheckFigureNameTest, AcceptsFileStemsOnly) {
  for (const char* name : {"learning_curves", "a", "fig-2.v1", "Schedule_Families"}) {
    EXPECT_TRUE(CheckFigureName(name).ok()) << name;
  }
  for (const char* name : {"", ".hidden", "-flag", "a/b", "../up", "with space", "quote'",
                           "semi;colon"}) {
    EXPECT_EQ(CheckFigureName(name).code(), absl::StatusCode::kInvalidArgument) << name;
  }
  EXPECT_FALSE(CheckFigureName(std::string(101, 'a')).ok());
}

TEST(SeriesColorTest, IsOkabeItoInAFixedOrderCyclingAfterEight) {
  EXPECT_EQ(SeriesColor(0), "#0072B2");
  EXPECT_EQ(SeriesColor(1), "#D55E00");
  EXPECT_EQ(SeriesColor(2), "#009E73");
  EXPECT_EQ(SeriesColor(8), SeriesColor(0));
  EXPECT_EQ(SeriesColor(17), SeriesColor(1));
}

TEST(GnuplotStringTest, SingleQuotesAndDoublesQuotes) {
  EXPECT_EQ(GnuplotString("plain"), "'plain'");
  EXPECT_EQ(GnuplotString("it's"), "'it''s'");
  // Backslashes and enhanced-text specials stay as they are: single-quoted strings do not
  // interpret backslashes, and the text is drawn noenhanced.
  EXPECT_EQ(GnuplotString(R"(a\nb "q" x_1 y^2 @ & {})"), R"('a\nb "q" x_1 y^2 @ & {}')");
  EXPECT_EQ(GnuplotString("two\nlines\tand\rtab"), "'two lines and tab'");
  EXPECT_EQ(GnuplotString(""), "''");
  EXPECT_EQ(GnuplotString("ü → τ"), "'ü → τ'");  // UTF-8 passes through
}

TEST(CsvFieldTest, QuotesOnlyWhatNeedsIt) {
  EXPECT_EQ(CsvField("sinusoidal"), "sinusoidal");
  EXPECT_EQ(CsvField("amplitude_frac 0.5, period 125"), "\"amplitude_frac 0.5, period 125\"");
  EXPECT_EQ(CsvField("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(CsvField("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(CsvField(""), "");
}

TEST(CsvNumberTest, KeepsEightSignificantDigitsAndStepsExact) {
  EXPECT_EQ(CsvNumber(0), "0");
  EXPECT_EQ(CsvNumber(-0.0), "0");
  EXPECT_EQ(CsvNumber(151552), "151552");
  EXPECT_EQ(CsvNumber(12345678), "12345678");
  EXPECT_EQ(CsvNumber(0.1), "0.1");
  EXPECT_EQ(CsvNumber(-1.0 / 3), "-0.33333333");
  EXPECT_EQ(CsvNumber(2.5e-7), "2.5e-07");
}

TEST(ScriptPreambleTest, ChoosesTheTerminalFromFormatAndWritesNameDotFormat) {
  const GnuplotFigure figure{.name = "curves",
                             .title = "Learning curves",
                             .data = {{.name = "curves.csv"}, {.name = "more.csv"}}};
  const std::string script = ScriptPreamble(figure, 800, 600);
  EXPECT_THAT(script, HasSubstr("# Learning curves\n"));
  EXPECT_THAT(script, HasSubstr("# Data: curves.csv, more.csv"));
  EXPECT_THAT(script, HasSubstr("gnuplot curves.gp"));
  EXPECT_THAT(script, HasSubstr("if (!exists('format')) format = 'svg'"));
  EXPECT_THAT(script, HasSubstr("set terminal svg size 800,600 fixed noenhanced"));
  EXPECT_THAT(script, HasSubstr("set terminal pngcairo size 800,600 noenhanced"));
  EXPECT_THAT(script, HasSubstr("set terminal pdfcairo size 8.00in,6.00in noenhanced"));
  EXPECT_THAT(script, HasSubstr("exit status 3"));
  EXPECT_THAT(script, HasSubstr("set output 'curves'.'.'.format\n"));
  EXPECT_THAT(script, HasSubstr("set datafile separator comma\n"));
  EXPECT_THAT(script, HasSubstr("set datafile columnheaders\n"));
  EXPECT_THAT(script, HasSubstr("fontsize = 12"));
}

TEST(KeyCommandTest, PlacesTheLegendOrRemovesIt) {
  EXPECT_EQ(KeyCommand(LegendPlace::kNone), "unset key\n");
  EXPECT_THAT(KeyCommand(LegendPlace::kTopLeft), HasSubstr("set key top left inside"));
  EXPECT_THAT(KeyCommand(LegendPlace::kOutsideRight), HasSubstr("outside"));
}

TEST(LayOutPanelsTest, FillsRowsOfAtMostColumnsPanels) {
  const PanelGrid eleven = LayOutPanels(11, 3, 400, 300, /*has_title=*/true);
  EXPECT_EQ(eleven.rows, 4);
  EXPECT_EQ(eleven.columns, 3);
  EXPECT_EQ(eleven.width, 1200);
  EXPECT_EQ(eleven.height, 4 * 300 + 36);
  const PanelGrid two = LayOutPanels(2, 3, 400, 300, /*has_title=*/false);
  EXPECT_EQ(two.columns, 2);  // only as wide as its panels
  EXPECT_EQ(two.rows, 1);
  EXPECT_EQ(two.width, 800);
  EXPECT_EQ(two.height, 300);
  EXPECT_EQ(MultiplotCommand(two, ""), "set multiplot layout 1,2\n\n");
  EXPECT_THAT(MultiplotCommand(eleven, "It's"),
              HasSubstr("set multiplot layout 4,3 title 'It''s' font"));
}

}  // namespace
}  // namespace dcs::report
