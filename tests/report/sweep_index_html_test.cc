// Copyright 2026 The DCS Authors.
#include "report/sweep_index_html.h"

#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

int Count(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

std::vector<GnuplotFigure> Figures() {
  return {{.name = "learning_curves",
           .title = "Learning curves: demo",
           .data = {{.name = "learning_curves.csv"}}},
          {.name = "family_heatmap",
           .title = "Relative to <static> & \"co\"",
           .data = {{.name = "family_heatmap.csv"}}}};
}

TEST(SweepIndexHtmlTest, ShowsTheTableAndEveryFigureWithItsDataAndScript) {
  const std::string html =
      SweepIndexHtml("Sweep demo", "<table><tr><td>1</td></tr></table>", Figures(),
                     FigureFormat::kSvg);
  EXPECT_TRUE(html.starts_with("<!DOCTYPE html>"));
  EXPECT_THAT(html, HasSubstr("<title>Sweep demo</title>"));
  EXPECT_THAT(html, HasSubstr("<table><tr><td>1</td></tr></table>"));
  EXPECT_EQ(Count(html, "<img "), 2);
  EXPECT_THAT(html, HasSubstr("<img src=\"learning_curves.svg\" alt=\"Learning curves: demo\">"));
  EXPECT_THAT(html, HasSubstr("<a href=\"learning_curves.csv\">learning_curves.csv</a>"));
  EXPECT_THAT(html, HasSubstr("<a href=\"learning_curves.gp\">learning_curves.gp</a>"));
  EXPECT_THAT(html, HasSubstr("<a href=\"family_heatmap.gp\">"));
  EXPECT_THAT(html, HasSubstr("<a href=\"#family_heatmap\">"));
  EXPECT_THAT(html, HasSubstr("</html>\n"));
}

TEST(SweepIndexHtmlTest, LoadsNothingButTheFiguresBesideIt) {
  const std::string html = SweepIndexHtml("t", "<table></table>", Figures(), FigureFormat::kPng);
  EXPECT_THAT(html, Not(HasSubstr("http")));
  EXPECT_THAT(html, Not(HasSubstr("<script")));
  EXPECT_THAT(html, Not(HasSubstr("<link")));
  EXPECT_THAT(html, Not(HasSubstr("src=\"/")));
  EXPECT_THAT(html, HasSubstr("<img src=\"family_heatmap.png\""));
}

TEST(SweepIndexHtmlTest, EscapesTitles) {
  const std::string html = SweepIndexHtml("a < b & 'c'", "", Figures(), FigureFormat::kSvg);
  EXPECT_THAT(html, HasSubstr("<h1>a &lt; b &amp; &#39;c&#39;</h1>"));
  EXPECT_THAT(html, HasSubstr("alt=\"Relative to &lt;static&gt; &amp; &quot;co&quot;\""));
  EXPECT_THAT(html, Not(HasSubstr("<static>")));
  EXPECT_THAT(html, Not(HasSubstr("id=\"report\"")));  // no table given
}

TEST(SweepIndexHtmlTest, EmbedsPdfsAsObjectsWithALink) {
  const std::string html = SweepIndexHtml("t", "", Figures(), FigureFormat::kPdf);
  EXPECT_EQ(Count(html, "<img "), 0);
  EXPECT_EQ(Count(html, "<object data=\""), 2);
  EXPECT_THAT(html, HasSubstr("<object data=\"learning_curves.pdf\" type=\"application/pdf\""));
  EXPECT_THAT(html, HasSubstr("<a href=\"learning_curves.pdf\">learning_curves.pdf</a>"));
}

}  // namespace
}  // namespace dcs::report
