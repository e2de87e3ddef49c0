// Copyright 2026 The DCS Authors.
#include "coordinator/pruners.h"

#include <cmath>
#include <map>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::Pair;

StudyTrial Complete(int64_t number, std::map<int64_t, double> reported) {
  return {.number = number, .state = TrialState::kComplete, .reported = std::move(reported)};
}

StudyTrial Running(int64_t number, std::map<int64_t, double> reported) {
  return {.number = number, .state = TrialState::kRunning, .reported = std::move(reported)};
}

// Five complete trials that reported 1..5 at step 3.
std::vector<StudyTrial> FiveAtStepThree() {
  std::vector<StudyTrial> trials;
  for (int i = 0; i < 5; ++i) trials.push_back(Complete(i, {{3, i + 1.0}}));
  return trials;
}

TEST(MedianPruneTest, PrunesATrialWorseThanTheMedianAtItsStep) {
  const std::vector<StudyTrial> trials = FiveAtStepThree();  // median 3
  const MedianPrunerOptions options;
  EXPECT_TRUE(MedianPrune(Running(9, {{3, 3.5}}), trials, Direction::kMinimize, options));
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 2.5}}), trials, Direction::kMinimize, options));
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 3.5}}), trials, Direction::kMaximize, options));
  EXPECT_TRUE(MedianPrune(Running(9, {{3, 2.5}}), trials, Direction::kMaximize, options));
  // Its best value at any step counts, not its last.
  EXPECT_FALSE(
      MedianPrune(Running(9, {{1, 1.0}, {3, 4.0}}), trials, Direction::kMinimize, options));
  // Another percentile: the 25th of 1..5 is 2.
  EXPECT_TRUE(MedianPrune(Running(9, {{3, 2.5}}), trials, Direction::kMinimize,
                          MedianPrunerOptions{.percentile = 25}));
  // A trial whose every value is NaN is pruned.
  EXPECT_TRUE(MedianPrune(Running(9, {{3, std::nan("")}}), trials, Direction::kMinimize, options));
}

TEST(MedianPruneTest, WaitsForStartupTrialsWarmupAndEnoughReports) {
  std::vector<StudyTrial> four = FiveAtStepThree();
  four.pop_back();
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 9.0}}), four, Direction::kMinimize, {}));
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 9.0}}), FiveAtStepThree(), Direction::kMinimize,
                           MedianPrunerOptions{.warmup_steps = 4}));
  // Nobody reported step 4: nothing to compare with.
  EXPECT_FALSE(MedianPrune(Running(9, {{4, 9.0}}), FiveAtStepThree(), Direction::kMinimize, {}));
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 9.0}}), FiveAtStepThree(), Direction::kMinimize,
                           MedianPrunerOptions{.min_trials = 6}));
  // Running and pruned trials are never the reference.
  std::vector<StudyTrial> others = {
      Running(0, {{3, 1.0}}), {.number = 1, .state = TrialState::kPruned, .reported = {{3, 1.0}}}};
  EXPECT_FALSE(MedianPrune(Running(9, {{3, 9.0}}), others, Direction::kMinimize,
                           MedianPrunerOptions{.startup_trials = 0}));
}

TEST(MedianPruneTest, ChecksOncePerInterval) {
  const MedianPrunerOptions every_two{.interval_steps = 2};
  std::vector<StudyTrial> trials;
  for (int i = 0; i < 5; ++i) trials.push_back(Complete(i, {{2, 1.0}, {3, 1.0}}));
  // Step 3's interval starts at 2, where the trial was already checked.
  EXPECT_FALSE(
      MedianPrune(Running(9, {{2, 9.0}, {3, 9.0}}), trials, Direction::kMinimize, every_two));
  // Its report before was at step 1, in the interval before.
  EXPECT_TRUE(
      MedianPrune(Running(9, {{1, 9.0}, {3, 9.0}}), trials, Direction::kMinimize, every_two));
}

TEST(SuccessiveHalvingPruneTest, OnlyTheBestOfEachRungGoOn) {
  const SuccessiveHalvingOptions halving{.min_resource = 1, .reduction_factor = 2};
  // The first trial at step 1 reaches rung 0 alone: it is the best there, and goes on.
  HalvingDecision first =
      SuccessiveHalvingPrune(Running(0, {{1, 5.0}}), {}, {}, {}, Direction::kMinimize, halving);
  EXPECT_FALSE(first.prune);
  EXPECT_THAT(first.rungs, ElementsAre(Pair(0, 5.0)));
  // A second, worse at rung 0, of two values: only the best one (2 / 2) goes on.
  EXPECT_TRUE(SuccessiveHalvingPrune(Running(1, {{1, 6.0}}), {}, {first.rungs}, {},
                                     Direction::kMinimize, halving)
                  .prune);
  EXPECT_FALSE(SuccessiveHalvingPrune(Running(1, {{1, 4.0}}), {}, {first.rungs}, {},
                                      Direction::kMinimize, halving)
                   .prune);
  EXPECT_FALSE(SuccessiveHalvingPrune(Running(1, {{1, 6.0}}), {}, {first.rungs}, {},
                                      Direction::kMaximize, halving)
                   .prune);
  // At step 4 a trial passes rungs 1 (step 2) and 2 (step 4) in one check, each recorded.
  const HalvingDecision later = SuccessiveHalvingPrune(
      Running(0, {{1, 5.0}, {4, 3.0}}), first.rungs, {}, {}, Direction::kMinimize, halving);
  EXPECT_FALSE(later.prune);
  EXPECT_THAT(later.rungs, ElementsAre(Pair(0, 5.0), Pair(1, 3.0), Pair(2, 3.0)));
  // NaN is pruned; with bootstrap_count 1, a rung of one value prunes.
  EXPECT_TRUE(SuccessiveHalvingPrune(Running(2, {{1, std::nan("")}}), {}, {}, {},
                                     Direction::kMinimize, halving)
                  .prune);
  SuccessiveHalvingOptions bootstrap = halving;
  bootstrap.bootstrap_count = 1;
  EXPECT_TRUE(
      SuccessiveHalvingPrune(Running(2, {{1, 1.0}}), {}, {}, {}, Direction::kMinimize, bootstrap)
          .prune);
}

TEST(SuccessiveHalvingPruneTest, AutoMinResourceComesFromTheFirstCompleteTrial) {
  const SuccessiveHalvingOptions automatic{.reduction_factor = 2};
  // No trial complete: nothing is decided or recorded.
  const HalvingDecision none =
      SuccessiveHalvingPrune(Running(1, {{300, 9.0}}), {}, {}, {}, Direction::kMinimize, automatic);
  EXPECT_FALSE(none.prune);
  EXPECT_THAT(none.rungs, IsEmpty());
  // Trial 0 completed at step 500: min_resource 5, so step 4 is before rung 0 and step 5 at it.
  const std::vector<StudyTrial> trials = {Complete(0, {{500, 1.0}})};
  EXPECT_THAT(SuccessiveHalvingPrune(Running(1, {{4, 9.0}}), {}, {}, trials, Direction::kMinimize,
                                     automatic)
                  .rungs,
              IsEmpty());
  EXPECT_THAT(SuccessiveHalvingPrune(Running(1, {{5, 9.0}}), {}, {}, trials, Direction::kMinimize,
                                     automatic)
                  .rungs,
              ElementsAre(Pair(0, 9.0)));
}

}  // namespace
}  // namespace dcs::coordinator
