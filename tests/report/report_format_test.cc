// Copyright 2026 The DCS Authors.
#include "report/report_format.h"

#include <string>
#include <vector>

#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/message_differencer.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "report/sweep_report.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A finished trial whose runs (seeds 0, 1, ...) score `scores`.
v1::TrialResults Trial(const std::string& condition, const std::string& family,
                       const std::string& observe, const std::vector<double>& scores) {
  v1::TrialResults trial;
  trial.set_condition(condition);
  trial.set_family(family);
  trial.set_observe(observe);
  for (size_t seed = 0; seed < scores.size(); ++seed) {
    v1::EvaluationLog* log = trial.add_runs();
    log->set_seed(seed);
    log->set_complete(true);
    log->add_evaluations()->set_avg_combined(scores[seed]);
    log->set_last(scores[seed]);
    log->set_best_anytime(scores[seed]);
  }
  return trial;
}

// The weird condition's name holds what every format must escape.
constexpr char kWeird[] = "a<b, & 50%#_x";

// Three conditions in two modes, 3 seeds: the weird condition has 2 runs in mode none (fewer
// than asked) and none yet in mode live; the static baseline scores negative.
v1::SweepReport SmallReport(bool with_static = true) {
  v1::SweepResults results;
  results.set_sweep_id("sweep-7");
  results.set_name("cartpole_families");
  results.set_seeds(3);
  std::vector<v1::TrialResults> trials = {
      Trial("sin_large", "sinusoidal", "none", {410, 420, 430}),
      Trial("sin_large", "sinusoidal", "live", {460, 470, 480}),
      Trial(kWeird, "random_walk", "none", {400, 405}),
      Trial(kWeird, "random_walk", "live", {})};
  if (with_static) {
    trials.push_back(Trial("static", "static", "none", {-80, -90, -70}));
    trials.push_back(Trial("static", "static", "live", {429, 401.5, 451.4}));
  }
  for (const v1::TrialResults& trial : trials) *results.add_trials() = trial;
  ReportOptions options;
  options.bootstrap_resamples = 500;
  options.bootstrap_seed = 3;
  absl::StatusOr<v1::SweepReport> report = BuildSweepReport(results, options);
  EXPECT_TRUE(report.ok()) << report.status();
  return report.ok() ? *report : v1::SweepReport();
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines = absl::StrSplit(text, '\n');
  EXPECT_EQ(lines.back(), "") << "every format ends with a newline";
  lines.pop_back();
  return lines;
}

TEST(ReportFormatTest, TableIsAlignedMarksTheBestAndStatesItsSettings) {
  const std::string table = FormatReport(SmallReport(), ReportFormat::kTable);
  const std::vector<std::string> lines = Lines(table);
  EXPECT_THAT(lines[0], HasSubstr("Sweep cartpole_families (sweep-7)"));
  EXPECT_THAT(lines[0], HasSubstr("avg_combined at the final evaluation (last checkpoint)"));
  EXPECT_THAT(lines[2], HasSubstr("CONDITION"));
  EXPECT_THAT(lines[2], HasSubstr("none:IQM [Q1, Q3]"));
  EXPECT_THAT(lines[2], HasSubstr("live:P(>baseline)"));
  // The baseline first, then the sweep's order; every line of the table as wide as its header.
  EXPECT_EQ(lines[3].rfind("static ", 0), 0u);
  EXPECT_EQ(lines[4].rfind("sin_large ", 0), 0u);
  EXPECT_EQ(lines[5].rfind(kWeird, 0), 0u);
  for (int i = 3; i <= 5; ++i) EXPECT_EQ(lines[i].size(), lines[2].size()) << lines[i];
  EXPECT_EQ(lines[6], "");
  // The best of none: sin_large's 420 over 402.5 and -80; of live: its 470 over 427.3.
  EXPECT_THAT(lines[4], HasSubstr("*420.0 [415.0, 425.0]"));
  EXPECT_THAT(lines[4], HasSubstr("*470.0 [465.0, 475.0]"));
  EXPECT_THAT(lines[3], Not(HasSubstr("*")));
  EXPECT_THAT(lines[5], HasSubstr("2/3"));
  EXPECT_THAT(lines[5], HasSubstr("0/3"));
  EXPECT_THAT(table, HasSubstr("500 resamples, seed 3"));
  EXPECT_THAT(table, HasSubstr("Q1, Q3 = the 25th and 75th percentiles"));
  EXPECT_THAT(table, HasSubstr("*: the best IQM of its mode"));
  EXPECT_THAT(table, HasSubstr("probability of improvement over static"));
}

TEST(ReportFormatTest, MarkdownIsAGithubTable) {
  const std::vector<std::string> lines =
      Lines(FormatReport(SmallReport(), ReportFormat::kMarkdown));
  EXPECT_EQ(lines[2],
            "| condition | family | none runs | none IQM [Q1, Q3] | none 95% CI | "
            "none P(>baseline) | none Holm p | live runs | live IQM [Q1, Q3] | live 95% CI | "
            "live P(>baseline) | live Holm p |");
  EXPECT_EQ(lines[3], "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
  EXPECT_EQ(lines[4].rfind("| static | static | 3/3 | -80.0 [-85.0, -75.0] |", 0), 0u) << lines[4];
  EXPECT_EQ(lines[5].rfind("| sin\\_large | sinusoidal | 3/3 | **420.0 [415.0, 425.0]** |", 0),
            0u)
      << lines[5];
  EXPECT_EQ(lines[6].rfind("| a\\<b, & 50%#\\_x | random\\_walk | 2/3 |", 0), 0u) << lines[6];
  EXPECT_EQ(lines[7], "");
  const std::string footer = absl::StrJoin(lines.begin() + 8, lines.end(), "\n");
  EXPECT_THAT(footer, HasSubstr("500 resamples, seed 3"));
  EXPECT_THAT(footer, HasSubstr("Q1, Q3 = the 25th and 75th percentiles"));
  EXPECT_THAT(footer, HasSubstr("Bold: the best IQM"));
}

TEST(ReportFormatTest, CsvHasOneRowPerConditionAndMode) {
  const std::vector<std::string> lines = Lines(FormatReport(SmallReport(), ReportFormat::kCsv));
  ASSERT_EQ(lines.size(), 1u + 3 * 2);
  EXPECT_EQ(lines[0],
            "checkpoint,split,condition,family,baseline,mode,runs,seeds,iqm,q1,q3,ci_low,"
            "ci_high,p_improvement,p_improvement_ci_low,p_improvement_ci_high,p_value,"
            "holm_p_value,significant,best");
  // The baseline's none cell: IQM of {-90, -80, -70} (3 runs: nothing trimmed).
  const std::vector<std::string> baseline = absl::StrSplit(lines[1], ',');
  ASSERT_EQ(baseline.size(), 20u);
  EXPECT_EQ(baseline[2], "static");
  EXPECT_EQ(baseline[4], "true");
  EXPECT_EQ(baseline[5], "none");
  EXPECT_EQ(baseline[6], "3");
  EXPECT_EQ(baseline[8], "-80");
  EXPECT_EQ(baseline[13], "");  // no improvement over itself
  EXPECT_EQ(baseline[18], "");  // nor a test
  EXPECT_EQ(baseline[19], "false");
  EXPECT_EQ(lines[3].rfind("last,combined,sin_large,sinusoidal,false,none,3,3,420,415,425,", 0),
            0u)
      << lines[3];
  EXPECT_THAT(lines[3], testing::EndsWith(",true"));
  // A name with a comma is quoted; an empty cell has empty numbers.
  EXPECT_EQ(lines[6], absl::StrCat("last,combined,\"", kWeird,
                                   "\",random_walk,false,live,0,3,,,,,,,,,,,,false"));
}

TEST(ReportFormatTest, JsonParsesBackToTheSameReport) {
  const v1::SweepReport report = SmallReport();
  const std::string json = FormatReport(report, ReportFormat::kJson);
  v1::SweepReport parsed;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(json, &parsed).ok()) << json;
  EXPECT_TRUE(google::protobuf::util::MessageDifferencer::Equals(parsed, report));
  EXPECT_THAT(json, HasSubstr("\"bootstrap_resamples\": 500"));
}

TEST(ReportFormatTest, LatexIsABooktabsTableWithEscapedNames) {
  const std::string latex = FormatReport(SmallReport(), ReportFormat::kLatex);
  EXPECT_THAT(latex, HasSubstr("\\begin{tabular}{llcccc}"));
  EXPECT_THAT(latex, HasSubstr("\\toprule"));
  EXPECT_THAT(latex, HasSubstr("\\midrule"));
  EXPECT_THAT(latex, HasSubstr("\\bottomrule"));
  EXPECT_THAT(latex, HasSubstr("\\multicolumn{2}{c}{none} & \\multicolumn{2}{c}{live}"));
  EXPECT_THAT(latex, HasSubstr("\\cmidrule(lr){3-4}\\cmidrule(lr){5-6}"));
  // Names escaped: _ & % # and <.
  EXPECT_THAT(latex, HasSubstr("sin\\_large & sinusoidal"));
  EXPECT_THAT(latex, HasSubstr("a\\textless{}b, \\& 50\\%\\#\\_x & random\\_walk"));
  EXPECT_THAT(latex, Not(HasSubstr("sin_large")));
  // IQM [Q1, Q3] cells, the best in bold, minus signs typeset, fewer runs marked, empty "--".
  EXPECT_THAT(latex, HasSubstr("\\textbf{420.0 [415.0, 425.0]}"));
  EXPECT_THAT(latex, HasSubstr("$-$80.0 [$-$85.0, $-$75.0]"));
  EXPECT_THAT(latex, HasSubstr("402.5 [401.2, 403.8]$^\\dagger$"));
  EXPECT_THAT(latex, HasSubstr("& -- & --"));
  // The caption states the checkpoint, split, seeds and bootstrap settings.
  const size_t caption = latex.find("\\caption{");
  ASSERT_NE(caption, std::string::npos);
  const std::string text = latex.substr(caption, latex.find("\\label{") - caption);
  EXPECT_THAT(text, HasSubstr("checkpoint last"));
  EXPECT_THAT(text, HasSubstr("split combined"));
  EXPECT_THAT(text, HasSubstr("3 seeds per condition"));
  EXPECT_THAT(text, HasSubstr("95\\% percentile intervals, 500 resamples, seed 3"));
  EXPECT_THAT(text, HasSubstr("25th and 75th percentiles"));
  EXPECT_THAT(text, HasSubstr("avg\\_combined"));
  EXPECT_THAT(latex, HasSubstr("\\label{tab:sweep-cartpole-families}"));
}

TEST(ReportFormatTest, LatexWithoutABaselineHasOneColumnPerMode) {
  const std::string latex = FormatReport(SmallReport(/*with_static=*/false), ReportFormat::kLatex);
  EXPECT_THAT(latex, HasSubstr("\\begin{tabular}{llcc}"));
  EXPECT_THAT(latex, HasSubstr("Condition & Family & none & live \\\\\n\\midrule"));
  EXPECT_THAT(latex, Not(HasSubstr("baseline")));
}

TEST(ReportFormatTest, HtmlEscapesText) {
  const std::string html = FormatReport(SmallReport(), ReportFormat::kHtml);
  EXPECT_EQ(html.rfind("<table class=\"dcs-sweep-report\">\n<caption>", 0), 0u);
  EXPECT_THAT(html, HasSubstr("</table>\n"));
  EXPECT_THAT(html, HasSubstr("<td>a&lt;b, &amp; 50%#_x</td>"));
  EXPECT_THAT(html, Not(HasSubstr("a<b")));
  EXPECT_THAT(html, HasSubstr("<th>P(&gt;baseline)</th>"));
  EXPECT_THAT(html, HasSubstr("<th colspan=\"5\">none</th>"));
  EXPECT_THAT(html, HasSubstr("<td><strong>470.0 [465.0, 475.0]</strong></td>"));
  EXPECT_THAT(html, HasSubstr("<tfoot>\n<tr><td colspan=\"12\">Bold: the best IQM"));
  EXPECT_THAT(html, HasSubstr("500 resamples, seed 3"));
}

TEST(ReportFormatTest, WithoutABaselineNoFormatHasAnImprovementColumn) {
  const v1::SweepReport report = SmallReport(/*with_static=*/false);
  for (const ReportFormat format : {ReportFormat::kTable, ReportFormat::kMarkdown,
                                    ReportFormat::kHtml}) {
    EXPECT_THAT(FormatReport(report, format), Not(HasSubstr("P(")));
  }
}

// SmallReport with a coverage section: two rows in mode none, one test with both statistics,
// one mode whose test has only a note.
v1::SweepReport WithCoverage() {
  v1::SweepReport report = SmallReport();
  v1::CoverageSection& section = *report.add_coverage();
  section.set_projection("state");
  section.set_cells(20736);
  for (const auto& [start, end] : {std::pair(0, 50'000), std::pair(50'000, 100'000),
                                    std::pair(100'000, 151'552)}) {
    section.add_window_starts(start);
    section.add_window_ends(end);
  }
  for (const char* condition : {"static", kWeird}) {
    v1::CoverageRow& row = *section.add_rows();
    row.set_condition(condition);
    row.set_mode("none");
    row.add_runs(6.5);
    row.add_runs(6.7);
    row.set_mean(6.6);
    row.set_sem(0.1);
    for (double mean : {6.45, 0.571, 0.27}) row.add_window_means(mean);
  }
  v1::CoverageTest& test = *section.add_tests();
  test.set_mode("none");
  test.mutable_anova()->set_f(1.25);
  test.mutable_anova()->set_df_between(1);
  test.mutable_anova()->set_df_within(2);
  test.mutable_anova()->set_p_value(0.38);
  test.mutable_correlation()->set_r(0.21);
  test.mutable_correlation()->set_p_value(0.003);
  test.mutable_correlation()->set_runs(4);
  section.add_tests()->set_mode("live");
  section.mutable_tests(1)->set_note("no ANOVA: a one-way ANOVA needs at least two groups, got 0");
  return report;
}

TEST(ReportFormatTest, CoverageFollowsTheScoresInTableMarkdownAndHtml) {
  const v1::SweepReport report = WithCoverage();
  const std::string table = FormatReport(report, ReportFormat::kTable);
  EXPECT_THAT(table, HasSubstr("\nCoverage of state (20736 cells): percent of the cells"));
  EXPECT_THAT(table, HasSubstr("0-50k %  50k-100k %  100k-151.552k %"));
  EXPECT_THAT(table, HasSubstr("6.60 +- 0.10"));
  EXPECT_THAT(table, HasSubstr("none: one-way ANOVA across conditions F(1, 2) = 1.25, p = 0.38; "
                               "Pearson r(score, coverage) = 0.210, p = 0.003 (4 runs).\n"));
  EXPECT_THAT(table, HasSubstr("live: no ANOVA: a one-way ANOVA needs at least two groups"));
  const std::string md = FormatReport(report, ReportFormat::kMarkdown);
  EXPECT_THAT(md, HasSubstr("| condition | mode | runs | run % | 0-50k % |"));
  EXPECT_THAT(md, HasSubstr("|---|---|--:|--:|--:|--:|--:|\n"));
  EXPECT_THAT(md, HasSubstr("| a\\<b, & 50%#\\_x | none | 2 | 6.60 +- 0.10 | 6.45 | 0.57 | 0.27 |"));
  const std::string html = FormatReport(report, ReportFormat::kHtml);
  EXPECT_THAT(html, HasSubstr("<table class=\"dcs-coverage\">\n<caption>Coverage of state"));
  EXPECT_THAT(html, HasSubstr("<td>a&lt;b, &amp; 50%#_x</td><td>none</td>"));
  // The score table only in csv and latex.
  for (const ReportFormat format : {ReportFormat::kCsv, ReportFormat::kLatex}) {
    EXPECT_EQ(FormatReport(report, format), FormatReport(SmallReport(), format));
  }
}

}  // namespace
}  // namespace dcs::report
