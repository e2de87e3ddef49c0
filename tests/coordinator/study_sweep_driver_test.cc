// Copyright 2026 The DCS Authors.
//
// StudySweepDriver: every open study sweep stepped at each tick, by the test's clock, with the
// spec read at submission kept (or read once from the store after a restart).

#include "coordinator/study_sweep_driver.h"

#include <memory>
#include <string>
#include <vector>

#include "absl/strings/str_replace.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/coordinator/study_sweep_fixture.h"

namespace dcs::coordinator {
namespace {

using ::testing::IsEmpty;
using ::testing::SizeIs;

class StudySweepDriverTest : public StudySweepFixture {
 protected:
  // A driver of the store, as the coordinator makes one when it starts.
  std::unique_ptr<StudySweepDriver> Driver() {
    return std::make_unique<StudySweepDriver>(*store_, Path("data"), *logs_);
  }

  // One tick of `driver`: the step of the one open sweep, or nullopt if none is open.
  std::optional<StudySweepStep> Tick(StudySweepDriver& driver) {
    absl::StatusOr<std::vector<StudySweepDriver::SweepTick>> ticks = driver.Tick(kNow);
    EXPECT_TRUE(ticks.ok()) << ticks.status();
    if (!ticks.ok() || ticks->empty()) return std::nullopt;
    EXPECT_THAT(*ticks, SizeIs(1));
    EXPECT_TRUE(ticks->front().step.ok()) << ticks->front().step.status();
    return ticks->front().step.value_or(StudySweepStep{});
  }

  // Trains both seeds' runs of the oldest queued trial to the end, scoring `score`.
  void FinishTrial(double score) {
    Train({{2000, score}}, true);
    Train({{2000, score}}, true);
  }
};

TEST_F(StudySweepDriverTest, AsksForTheNextTrialWhenOneFinishes) {
  const SweepRecord sweep = Submit(kSpec);
  std::unique_ptr<StudySweepDriver> driver = Driver();
  driver->Adopt(sweep.id, spec_);
  EXPECT_EQ(Tick(*driver)->asked, 2);  // parallel: 2
  EXPECT_EQ(Tick(*driver)->asked, 0);  // nothing finished
  FinishTrial(10);
  const StudySweepStep step = *Tick(*driver);
  EXPECT_EQ(step.told, 1);
  EXPECT_EQ(step.asked, 1);
  EXPECT_THAT(Trials(sweep), SizeIs(3));
}

TEST_F(StudySweepDriverTest, StopsWhenTheStudysBudgetIsSpent) {
  const SweepRecord sweep = Submit(kSpec);
  std::unique_ptr<StudySweepDriver> driver = Driver();
  Tick(*driver);
  for (double score : {10.0, 20.0, 30.0, 40.0, 50.0}) {  // trials: 5
    FinishTrial(score);
    Tick(*driver);
  }
  EXPECT_THAT(Trials(sweep), SizeIs(5));
  absl::StatusOr<SweepRecord> closed = store_->sweeps().GetSweep(sweep.id);
  ASSERT_TRUE(closed.ok());
  EXPECT_FALSE(closed->open);
  EXPECT_THAT(closed->trials, SizeIs(7));  // and the two best retrained
  // A closed sweep is stepped no more: its retrained runs finish, and no trial is asked.
  for (int i = 0; i < 6; ++i) Train({{2000, 1.0}}, true);
  EXPECT_EQ(Tick(*driver), std::nullopt);
  EXPECT_THAT(Trials(sweep), SizeIs(5));
}

// A coordinator that restarts makes a new driver, which reads the open sweep's spec from the
// store and goes on where the last one stopped.
TEST_F(StudySweepDriverTest, ResumesAfterARestart) {
  const SweepRecord sweep = Submit(kSpec);
  EXPECT_EQ(Tick(*Driver())->asked, 2);
  FinishTrial(10);
  std::unique_ptr<StudySweepDriver> restarted = Driver();
  const StudySweepStep step = *Tick(*restarted);
  EXPECT_EQ(step.told, 1);
  EXPECT_EQ(step.asked, 1);  // trial 2: trials 0 and 1 are not asked again
  EXPECT_THAT(Trials(sweep), SizeIs(3));
}

// The spec handed over at submission is the one the sweep is stepped by: the spec text kept
// in the store is not read again (here they differ, which no submission makes).
TEST_F(StudySweepDriverTest, StepsBySpecItWasHandedNotByReadingTheTextAgain) {
  const SweepRecord sweep = Submit(kSpec);
  absl::StatusOr<ExpandedSweep> one_at_a_time = ExpandSweep(
      absl::StrReplaceAll(kSpec, {{"parallel: 2", "parallel: 1"}}), "search.yaml", "", "other");
  ASSERT_TRUE(one_at_a_time.ok()) << one_at_a_time.status();
  std::unique_ptr<StudySweepDriver> driver = Driver();
  driver->Adopt(sweep.id, *one_at_a_time->study);
  EXPECT_EQ(Tick(*driver)->asked, 1);
}

TEST_F(StudySweepDriverTest, ASweepWhoseSpecDoesNotReadIsReportedAndTheOthersStep) {
  const SweepRecord sweep = Submit(kSpec);
  std::unique_ptr<StudySweepDriver> driver = Driver();
  // A store written by another version may hold a spec this one refuses.
  SweepSubmission other{.request_id = "other",
                        .name = "other",
                        .spec = "seeds: [",
                        .seeds = 1,
                        .study = spec_.study};
  other.study->request_id = "other";
  absl::StatusOr<SweepRecord> unreadable = store_->sweeps().SubmitSweep(other, kNow);
  ASSERT_TRUE(unreadable.ok()) << unreadable.status();
  absl::StatusOr<std::vector<StudySweepDriver::SweepTick>> ticks = driver->Tick(kNow);
  ASSERT_TRUE(ticks.ok()) << ticks.status();
  ASSERT_THAT(*ticks, SizeIs(2));
  EXPECT_EQ((*ticks)[0].sweep_id, sweep.id);
  EXPECT_EQ((*ticks)[0].step->asked, 2);
  EXPECT_EQ((*ticks)[1].sweep_id, unreadable->id);
  EXPECT_EQ((*ticks)[1].step.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(Trials(*unreadable), IsEmpty());
}

}  // namespace
}  // namespace dcs::coordinator
