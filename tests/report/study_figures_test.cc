// Copyright 2026 The DCS Authors.
#include "report/study_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::report {
namespace {

using ::testing::HasSubstr;

coordinator::StudyTrial Trial(int64_t number, coordinator::TrialState state, double value) {
  return {.number = number, .state = state, .value = value};
}

// Complete trials' values as dots (line 0), the best so far as steps (line 1); the rest left
// out. The CSV's rows are panel,line,x,y,panel_title,label (report/line_chart.h).
TEST(StudyHistoryFigureTest, DrawsEachValueAndTheBestSoFar) {
  const coordinator::StudyRecord study{
      .id = "study-3", .submission = {.direction = coordinator::Direction::kMinimize}};
  const std::vector<coordinator::StudyTrial> trials = {
      Trial(0, coordinator::TrialState::kComplete, 5),
      Trial(1, coordinator::TrialState::kFailed, std::nan("")),
      Trial(2, coordinator::TrialState::kComplete, 7),
      Trial(3, coordinator::TrialState::kComplete, 2),
      Trial(4, coordinator::TrialState::kRunning, std::nan("")),
      Trial(5, coordinator::TrialState::kComplete, std::numeric_limits<double>::infinity())};
  const absl::StatusOr<GnuplotFigure> figure = StudyHistoryFigure(study, trials);
  ASSERT_TRUE(figure.ok()) << figure.status();
  EXPECT_EQ(figure->name, "study-3_history");
  ASSERT_EQ(figure->data.size(), 1u);
  const std::string& csv = figure->data[0].csv;
  EXPECT_THAT(csv, HasSubstr("0,0,0,5,"));
  EXPECT_THAT(csv, HasSubstr("0,0,2,7,"));
  EXPECT_THAT(csv, HasSubstr("0,0,3,2,"));
  EXPECT_THAT(csv, HasSubstr("0,1,0,5,"));
  EXPECT_THAT(csv, HasSubstr("0,1,2,5,"));  // 7 is no better than 5
  EXPECT_THAT(csv, HasSubstr("0,1,3,2,"));
  // Trials 1 (failed), 4 (running) and 5 (infinite) are not drawn: three rows per line.
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3);
  EXPECT_THAT(figure->script, HasSubstr("with points"));
  EXPECT_THAT(figure->script, HasSubstr("with steps"));
}

TEST(StudyHistoryFigureTest, MaximisingKeepsTheHighestAndNothingToDrawIsAnError) {
  const coordinator::StudyRecord study{
      .id = "study-1", .submission = {.direction = coordinator::Direction::kMaximize}};
  const absl::StatusOr<GnuplotFigure> figure =
      StudyHistoryFigure(study, {Trial(0, coordinator::TrialState::kComplete, 5),
                                 Trial(1, coordinator::TrialState::kComplete, 7)});
  ASSERT_TRUE(figure.ok()) << figure.status();
  EXPECT_THAT(figure->data[0].csv, HasSubstr("0,1,1,7,"));
  EXPECT_EQ(StudyHistoryFigure(study, {Trial(0, coordinator::TrialState::kRunning, std::nan(""))})
                .status()
                .code(),
            absl::StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace dcs::report
