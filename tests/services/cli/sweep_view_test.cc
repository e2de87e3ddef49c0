// Copyright 2026 The DCS Authors.
#include "services/cli/sweep_view.h"

#include <cmath>
#include <string>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A sweep of two trials x 2 seeds: trial 0 has both runs completed (scores 400, 420), trial 1
// one completed (450) and one running at 5000 of 10000 steps, 1000 steps/s.
v1::GetSweepResponse Sweep() {
  v1::GetSweepResponse response;
  v1::Sweep& sweep = *response.mutable_sweep();
  sweep.set_sweep_id("sweep-2");
  sweep.set_name("grid");
  sweep.set_state(v1::SWEEP_STATE_RUNNING);
  sweep.set_seeds(2);
  sweep.set_runs(4);
  sweep.set_completed(3);
  sweep.set_running(1);
  for (const char* condition : {"static", "sinusoidal"}) {
    v1::Trial& trial = *sweep.add_trials();
    trial.set_condition(condition);
    trial.set_observe("none");
  }
  auto add_run = [&](int trial, v1::RunState state, double avg_combined) {
    v1::Run& run = *response.add_runs();
    run.set_trial(trial);
    run.set_state(state);
    run.mutable_progress()->set_total_timesteps(10'000);
    if (state == v1::RUN_STATE_COMPLETED) {
      run.mutable_progress()->set_timesteps(10'000);
      run.mutable_progress()->set_avg_combined(avg_combined);
    } else {
      run.mutable_progress()->set_timesteps(5'000);
      run.mutable_progress()->set_steps_per_second(1'000);
    }
  };
  add_run(0, v1::RUN_STATE_COMPLETED, 400);
  add_run(0, v1::RUN_STATE_COMPLETED, 420);
  add_run(1, v1::RUN_STATE_COMPLETED, 450);
  add_run(1, v1::RUN_STATE_RUNNING, 0);
  return response;
}

TEST(SweepViewTest, TheHeadlineCountsRunsAndGivesPaceEtaAndTheBestTrial) {
  EXPECT_EQ(SweepHeadline(Sweep()),
            "sweep-2 grid: running, 3/4 runs done (1 running, 0 queued, 0 failed), 1000 "
            "steps/s, ETA 5s, best: sinusoidal (none) 450.0");
}

TEST(SweepViewTest, TheViewHasARowPerTrial) {
  const std::string view = SweepProgressView(Sweep());
  EXPECT_THAT(view, HasSubstr("CONDITION   MODE  DONE  RUNNING  QUEUED  FAILED  LAST (IQM)\n"
                              "static      none  2/2   0        0       0       410.0\n"
                              "sinusoidal  none  1/2   1        0       0       450.0\n"));
}

TEST(SweepViewTest, NoPaceOrBestBeforeAnyRunMovesOrEnds) {
  v1::GetSweepResponse sweep = Sweep();
  sweep.clear_runs();
  const std::string headline = SweepHeadline(sweep);
  EXPECT_THAT(headline, Not(HasSubstr("steps/s")));
  EXPECT_THAT(headline, Not(HasSubstr("best")));
  EXPECT_THAT(SweepProgressView(sweep), HasSubstr("static      none  0/2   0        0       0       -"));
}

TEST(SweepViewTest, AScoreThatIsNotANumberIsShownAsAnErrorNotAsNoneYet) {
  v1::GetSweepResponse sweep = Sweep();
  sweep.mutable_runs(2)->mutable_progress()->set_avg_combined(std::nan(""));
  EXPECT_THAT(SweepProgressView(sweep),
              HasSubstr("sinusoidal  none  1/2   1        0       0       error: "));
  EXPECT_THAT(SweepHeadline(sweep), HasSubstr("best: static (none) 410.0"));
}

}  // namespace
}  // namespace dcs::services::cli
