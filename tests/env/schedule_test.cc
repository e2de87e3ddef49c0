// Copyright 2026 The DCS Authors.
//
// The schedule families (docs/reference.md, "Schedule families"), built as users build them:
// MakeSchedule(ParseScheduleSpec(config, min, max, seed)), and driven by the Reset/Next protocol
// of env/schedule.h (v = Reset(initial, id); v = Next(k, v) for k = 1, 2, ...).
//
// Statistical tests use fixed seeds, so they are deterministic; their bounds are justified in
// comments (at least 5 standard errors from the expected value, so a correct implementation
// passes with any seed and an implementation with the wrong rate or scale fails).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "env/schedule.h"
#include "env/schedule_config.h"
#include "env/schedule_spec.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/env/schedule_test_config.h"

namespace dcs::env {
namespace {

using ::testing::AllOf;
using ::testing::Ge;
using ::testing::Le;


ScheduleSpec Spec(const ScheduleConfig& config, double min_value, double max_value,
                  uint32_t seed = 7) {
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, min_value, max_value, seed);
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *spec : ScheduleSpec{};
}

std::unique_ptr<Schedule> Build(const ScheduleConfig& config, double min_value, double max_value,
                                uint32_t seed = 7) {
  return MakeSchedule(Spec(config, min_value, max_value, seed));
}

// One episode: element 0 is Reset's value, element k the value of call k (k = 1..calls), each
// call given the previous value as the current one (as the wrapper does).
std::vector<double> RunEpisode(Schedule& schedule, double initial, EpisodeId id, int calls) {
  std::vector<double> values;
  values.reserve(calls + 1);
  values.push_back(schedule.Reset(initial, id));
  for (int k = 1; k <= calls; ++k) values.push_back(schedule.Next(k, values.back()));
  return values;
}

// The calls k at which the value changed (values[k] != values[k - 1]).
std::vector<int> ChangeCalls(const std::vector<double>& values) {
  std::vector<int> calls;
  for (size_t k = 1; k < values.size(); ++k) {
    if (values[k] != values[k - 1]) calls.push_back(static_cast<int>(k));
  }
  return calls;
}

// The calls k at which the value moved by more than `tolerance`.
std::vector<int> MoveCalls(const std::vector<double>& values, double tolerance) {
  std::vector<int> calls;
  for (size_t k = 1; k < values.size(); ++k) {
    if (std::abs(values[k] - values[k - 1]) > tolerance) calls.push_back(static_cast<int>(k));
  }
  return calls;
}

double Mean(const std::vector<double>& x) {
  double sum = 0;
  for (double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

double StdDev(const std::vector<double>& x) {
  const double mean = Mean(x);
  double sum = 0;
  for (double v : x) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(x.size() - 1));
}

// ---------------------------------------------------------------------------------------------
// Sinusoidal

TEST(ScheduleSinusoidalTest, FollowsBaselineMinusAmplitudeSine) {
  // Bounds [0, 2]: span 2, so amplitude_frac 0.25 is 0.25 * span/2 = 0.25 (a fraction of the
  // HALF range). Baseline 1 +- 0.25 stays well inside the bounds: no reflection.
  auto schedule = Build(Config("sinusoidal", {{"amplitude_frac", 0.25},
                                              {"period", 40.0},
                                              {"initial_direction", std::string("down")}}),
                        0, 2);
  const std::vector<double> v = RunEpisode(*schedule, 1.0, {}, 200);
  EXPECT_DOUBLE_EQ(v[0], 1.0);
  for (int k = 1; k <= 200; ++k) {
    EXPECT_NEAR(v[k], 1.0 - 0.25 * std::sin(2 * std::numbers::pi * k / 40.0), 1e-12) << k;
  }
}

TEST(ScheduleSinusoidalTest, PeakToPeakIsTwiceTheAmplitudeAndPeriodRepeats) {
  // amplitude_frac 0.5 of span/2 = 0.5 * 3 = 1.5 on [-3, 3]; baseline 0.
  auto schedule = Build(Config("sinusoidal", {{"amplitude_frac", 0.5}, {"period", 24.0}}), -3, 3);
  const std::vector<double> v = RunEpisode(*schedule, 0.0, {.episode = 3}, 96);
  const auto [lo, hi] = std::minmax_element(v.begin() + 1, v.end());
  // Period 24 is a multiple of 4, so the extremes (quarter periods) are sampled exactly.
  EXPECT_NEAR(*hi - *lo, 2 * 1.5, 1e-12);
  EXPECT_NEAR(*hi, 1.5, 1e-12);
  EXPECT_NEAR(*lo, -1.5, 1e-12);
  for (int k = 1; k + 24 <= 96; ++k) EXPECT_NEAR(v[k + 24], v[k], 1e-12) << k;
  // ... and not before: half a period later the value is mirrored about the baseline.
  EXPECT_NEAR(v[6 + 12], -v[6], 1e-12);
  EXPECT_GT(std::abs(v[6]), 1.0);
}

TEST(ScheduleSinusoidalTest, InitialDirectionDownAndUp) {
  const double kOmega = 2 * std::numbers::pi / 20;
  auto down = Build(Config("sinusoidal", {{"amplitude", 0.1},
                                          {"period", 20.0},
                                          {"initial_direction", std::string("down")}}),
                    0, 1);
  auto up = Build(Config("sinusoidal", {{"amplitude", 0.1},
                                        {"period", 20.0},
                                        {"initial_direction", std::string("up")}}),
                  0, 1);
  for (uint64_t episode = 0; episode < 5; ++episode) {
    const std::vector<double> d = RunEpisode(*down, 0.5, {.episode = episode}, 5);
    const std::vector<double> u = RunEpisode(*up, 0.5, {.episode = episode}, 5);
    EXPECT_NEAR(d[1], 0.5 - 0.1 * std::sin(kOmega), 1e-12);
    EXPECT_NEAR(u[1], 0.5 + 0.1 * std::sin(kOmega), 1e-12);
    EXPECT_LT(d[1], 0.5);
    EXPECT_GT(u[1], 0.5);
  }
}

TEST(ScheduleSinusoidalTest, RandomInitialDirectionTakesBothWays) {
  // initial_direction random (the default): +-1 with probability 1/2 per episode. Of 400
  // episodes, the number going down first is Binomial(400, 1/2): mean 200, sd 10; accept
  // 200 +- 50 (5 sd).
  auto schedule = Build(Config("sinusoidal", {{"amplitude", 0.1}, {"period", 20.0}}), 0, 1, 11);
  int down = 0;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 1);
    ASSERT_NE(v[1], 0.5);
    if (v[1] < 0.5) ++down;
  }
  EXPECT_THAT(down, AllOf(Ge(150), Le(250)));
}

TEST(ScheduleSinusoidalTest, ReflectsThePhaseDirectionInsteadOfLeavingTheBounds) {
  // Baseline 0.1 on [0, 1] with amplitude 0.3, going down first: call 1 gives
  // 0.1 - 0.3 sin(w) = 0.007 > 0, call 2 would give 0.1 - 0.3 sin(2w) < 0, so the direction
  // reverses and the phase steps back to 0 (value 0.1), then continues upwards.
  const double w = 2 * std::numbers::pi / 20;
  auto schedule = Build(Config("sinusoidal", {{"amplitude", 0.3},
                                              {"period", 20.0},
                                              {"initial_direction", std::string("down")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.1, {}, 60);
  EXPECT_NEAR(v[1], 0.1 - 0.3 * std::sin(w), 1e-12);
  EXPECT_NEAR(v[2], 0.1, 1e-12);
  EXPECT_NEAR(v[3], 0.1 + 0.3 * std::sin(w), 1e-12);
  EXPECT_NEAR(v[4], 0.1 + 0.3 * std::sin(2 * w), 1e-12);
  // Never clipped: a reflecting trajectory never touches the bound.
  for (size_t k = 1; k < v.size(); ++k) {
    EXPECT_GT(v[k], 0.0) << k;
    EXPECT_LE(v[k], 1.0) << k;
  }
}

// ---------------------------------------------------------------------------------------------
// Cosine annealing

// end + (start - end) * (1 + cos(pi * t / (T - 1))) / 2.
double Cosine(double start, double end, int64_t t, int64_t length) {
  const double f = static_cast<double>(std::clamp<int64_t>(t, 0, length - 1)) /
                   static_cast<double>(length - 1);
  return end + (start - end) * 0.5 * (1 + std::cos(std::numbers::pi * f));
}

TEST(ScheduleCosineAnnealingTest, OnceReachesEndAtTMaxMinusOneAndStays) {
  auto schedule = Build(Config("cosine_annealing", {{"mode", std::string("once")},
                                                    {"T_max", 101.0},
                                                    {"direction", std::string("to_max")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.3, {}, 150);
  EXPECT_DOUBLE_EQ(v[0], 0.3);
  for (int k = 1; k <= 150; ++k) EXPECT_NEAR(v[k], Cosine(0.3, 1.0, k, 101), 1e-12) << k;
  EXPECT_LT(v[99], 1.0);
  EXPECT_DOUBLE_EQ(v[100], 1.0);  // t = T_max - 1
  for (int k = 100; k <= 150; ++k) EXPECT_DOUBLE_EQ(v[k], 1.0) << k;
  // The cosine's midpoint is at t = (T - 1) / 2.
  EXPECT_NEAR(v[50], 0.65, 1e-12);
  // Monotone between start and end.
  for (int k = 1; k <= 100; ++k) EXPECT_GE(v[k], v[k - 1]) << k;
}

TEST(ScheduleCosineAnnealingTest, OnceWithExplicitStartAndEnd) {
  auto schedule = Build(Config("cosine_annealing", {{"mode", std::string("once")},
                                                    {"T_max", 11.0},
                                                    {"start", 0.8},
                                                    {"end", 0.2}}),
                        0, 1);
  // start overrides the episode-initial value.
  const std::vector<double> v = RunEpisode(*schedule, 0.5, {}, 12);
  EXPECT_DOUBLE_EQ(v[0], 0.8);
  EXPECT_NEAR(v[5], 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(v[10], 0.2);
  EXPECT_DOUBLE_EQ(v[12], 0.2);
}

TEST(ScheduleCosineAnnealingTest, CycleRestartRepeatsEveryT0Calls) {
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 50.0},
                                                    {"retarget", std::string("restart")},
                                                    {"direction", std::string("to_max")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.3, {}, 200);
  for (int k = 1; k < 50; ++k) EXPECT_NEAR(v[k], Cosine(0.3, 1.0, k, 50), 1e-12) << k;
  EXPECT_DOUBLE_EQ(v[49], 1.0);  // the first cycle ends at t = T_0 - 1
  EXPECT_DOUBLE_EQ(v[50], 0.3);  // k = T_0: a new cycle from the episode's start
  EXPECT_DOUBLE_EQ(v[100], 0.3);
  EXPECT_DOUBLE_EQ(v[150], 0.3);
  for (int k = 1; k + 50 <= 200; ++k) EXPECT_NEAR(v[k + 50], v[k], 1e-12) << k;
}

TEST(ScheduleCosineAnnealingTest, CycleTMultGrowsTheCycles) {
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 10.0},
                                                    {"T_mult", 2.0},
                                                    {"retarget", std::string("restart")},
                                                    {"direction", std::string("to_min")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.6, {}, 80);
  // Cycles start at k = 10 (length 20) and k = 30 (length 40), each from 0.6 towards 0.
  EXPECT_DOUBLE_EQ(v[9], 0.0);
  EXPECT_DOUBLE_EQ(v[10], 0.6);
  EXPECT_NEAR(v[20], Cosine(0.6, 0.0, 10, 20), 1e-12);
  EXPECT_DOUBLE_EQ(v[29], 0.0);
  EXPECT_DOUBLE_EQ(v[30], 0.6);
  EXPECT_NEAR(v[50], Cosine(0.6, 0.0, 20, 40), 1e-12);
  EXPECT_DOUBLE_EQ(v[69], 0.0);
  EXPECT_DOUBLE_EQ(v[70], 0.6);
}

TEST(ScheduleCosineAnnealingTest, CycleSwapStartsFromThePreviousEnd) {
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 50.0},
                                                    {"retarget", std::string("swap")},
                                                    {"direction", std::string("to_max")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.3, {}, 160);
  EXPECT_DOUBLE_EQ(v[49], 1.0);
  // The second cycle starts at 1.0, which sits on the high edge, so it heads for the low one.
  EXPECT_DOUBLE_EQ(v[50], 1.0);
  for (int k = 50; k < 100; ++k) EXPECT_NEAR(v[k], Cosine(1.0, 0.0, k - 50, 50), 1e-12) << k;
  EXPECT_DOUBLE_EQ(v[99], 0.0);
  // The third starts at 0.0 (the low edge) and heads back up.
  EXPECT_DOUBLE_EQ(v[100], 0.0);
  EXPECT_DOUBLE_EQ(v[149], 1.0);
}

TEST(ScheduleCosineAnnealingTest, CycleRandomRetargetSwapsOrRestarts) {
  // retarget random: at each new cycle, swap (start from the last end, 1.0) or restart (from
  // the episode's start, 0.3) with probability 1/2. Over 40 episodes both occur (each outcome
  // has probability 2^-40 of never happening), and nothing else.
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 10.0},
                                                    {"retarget", std::string("random")},
                                                    {"direction", std::string("to_max")}}),
                        0, 1, 71);
  std::set<double> second_cycle_starts;
  for (uint64_t episode = 0; episode < 40; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.3, {.episode = episode}, 10);
    EXPECT_DOUBLE_EQ(v[9], 1.0);
    second_cycle_starts.insert(std::round(v[10] * 1e9) / 1e9);  // up to rounding
  }
  EXPECT_EQ(second_cycle_starts, (std::set<double>{0.3, 1.0}));
}

TEST(ScheduleCosineAnnealingTest, AutoDirectionPicksTheFartherEdge) {
  auto schedule = Build(
      Config("cosine_annealing", {{"mode", std::string("once")}, {"T_max", 21.0}}), 0, 1);
  // Default direction auto. From 0.3 the farther edge is 1; from 0.7 it is 0 (the reference's code
  // comment says "nearest" but the reference picks the farther edge).
  EXPECT_DOUBLE_EQ(RunEpisode(*schedule, 0.3, {}, 20).back(), 1.0);
  EXPECT_DOUBLE_EQ(RunEpisode(*schedule, 0.7, {}, 20).back(), 0.0);
}

TEST(ScheduleCosineAnnealingTest, ToMinAndToMaxDirections) {
  auto to_min = Build(Config("cosine_annealing", {{"mode", std::string("once")},
                                                  {"T_max", 21.0},
                                                  {"direction", std::string("to_min")}}),
                      0, 1);
  auto to_max = Build(Config("cosine_annealing", {{"mode", std::string("once")},
                                                  {"T_max", 21.0},
                                                  {"direction", std::string("to_max")}}),
                      0, 1);
  // 0.8 is nearer the top, but to_min goes to the bottom anyway (and vice versa).
  EXPECT_DOUBLE_EQ(RunEpisode(*to_min, 0.8, {}, 20).back(), 0.0);
  EXPECT_DOUBLE_EQ(RunEpisode(*to_max, 0.2, {}, 20).back(), 1.0);
  // A start within repel_edge_eps_frac (0.05) of the band's edge heads for the other edge,
  // whatever the direction.
  EXPECT_DOUBLE_EQ(RunEpisode(*to_min, 0.02, {}, 20).back(), 1.0);
  EXPECT_DOUBLE_EQ(RunEpisode(*to_max, 0.98, {}, 20).back(), 0.0);
}

TEST(ScheduleCosineAnnealingTest, NeighbourhoodBandLimitsTheCycle) {
  // neighborhood_radius_frac 0.2 on [0, 1]: r = 0.5 * 0.2 * 1 = 0.1 (a fraction of span/2).
  // From 0.05 the band is [max(0, -0.05), 0.15] = [0, 0.15]; auto heads for its farther edge.
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 30.0},
                                                    {"neighborhood_radius_frac", 0.2},
                                                    {"retarget", std::string("restart")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.05, {}, 90);
  EXPECT_NEAR(v[29], 0.15, 1e-12);
  for (double value : v) EXPECT_THAT(value, AllOf(Ge(0.0), Le(0.15 + 1e-12)));
}

TEST(ScheduleCosineAnnealingTest, ReflectsBackIntoTheBand) {
  // Band [0.4, 0.6] around 0.5; to_max picks 0.6, but min_delta 0.3 pushes the end to 0.8,
  // outside the band: the overshoot is reflected about 0.6, so every value stays in the band.
  auto schedule = Build(Config("cosine_annealing", {{"T_0", 40.0},
                                                    {"neighborhood_radius", 0.1},
                                                    {"min_delta", 0.3},
                                                    {"direction", std::string("to_max")}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.5, {}, 39);
  for (double value : v) EXPECT_THAT(value, AllOf(Ge(0.4 - 1e-12), Le(0.6 + 1e-12)));
  EXPECT_NEAR(v[39], 2 * 0.6 - 0.8, 1e-12);  // the end 0.8, reflected
}

// ---------------------------------------------------------------------------------------------
// Continuous incrementer

TEST(ScheduleContinuousIncrementerTest, FirstCallIsANoOpThenConstantSteps) {
  auto up = Build(Config("continuous_incrementer", {{"delta_frac", 0.01},
                                                    {"episode_direction", std::string("up")},
                                                    {"follow_predefined_prob", 1.0}}),
                  0, 2);  // delta = 0.01 * span = 0.02
  const std::vector<double> v = RunEpisode(*up, 0.5, {}, 20);
  EXPECT_DOUBLE_EQ(v[0], 0.5);
  EXPECT_DOUBLE_EQ(v[1], 0.5);  // the first-call skip
  for (int k = 2; k <= 20; ++k) EXPECT_NEAR(v[k] - v[k - 1], 0.02, 1e-12) << k;

  auto down = Build(Config("continuous_incrementer", {{"delta", 0.03},
                                                      {"episode_direction", std::string("down")},
                                                      {"follow_predefined_prob", 1.0}}),
                    0, 2);
  const std::vector<double> d = RunEpisode(*down, 1.5, {}, 20);
  EXPECT_DOUBLE_EQ(d[1], 1.5);
  for (int k = 2; k <= 20; ++k) EXPECT_NEAR(d[k] - d[k - 1], -0.03, 1e-12) << k;
}

TEST(ScheduleContinuousIncrementerTest, ReflectionAtABoundFlipsTheSign) {
  // Default edge_mode reflect. Up from 0.975 by 0.01: 0.985, 0.995, then 1.005 reflects to
  // 0.995 and the direction turns: 0.985, 0.975, ...
  auto schedule = Build(Config("continuous_incrementer", {{"delta", 0.01},
                                                          {"episode_direction", std::string("up")},
                                                          {"follow_predefined_prob", 1.0}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.975, {}, 8);
  const std::vector<double> expected = {0.975, 0.975, 0.985, 0.995, 0.995,
                                        0.985, 0.975, 0.965, 0.955};
  ASSERT_EQ(v.size(), expected.size());
  for (size_t k = 0; k < v.size(); ++k) EXPECT_NEAR(v[k], expected[k], 1e-12) << k;
}

TEST(ScheduleContinuousIncrementerTest, ClipEdgeModeHoldsAtTheBound) {
  auto schedule = Build(Config("continuous_incrementer", {{"delta", 0.01},
                                                          {"edge_mode", std::string("clip")},
                                                          {"episode_direction", std::string("up")},
                                                          {"follow_predefined_prob", 1.0}}),
                        0, 1);
  const std::vector<double> v = RunEpisode(*schedule, 0.975, {}, 8);
  EXPECT_NEAR(v[3], 0.995, 1e-12);
  for (int k = 4; k <= 8; ++k) EXPECT_DOUBLE_EQ(v[k], 1.0) << k;
}

TEST(ScheduleContinuousIncrementerTest, MeanDriftIsTwoPMinusOneTimesDelta) {
  // Builder default follow_predefined_prob p = 0.8: each step keeps the sign with probability
  // 0.8, so the mean step is (2p - 1) * delta = 0.6 * delta, with sd 2 * sqrt(p(1-p)) * delta =
  // 0.8 * delta. 400 episodes x 100 steps = 40000 steps: the standard error of the mean step is
  // 0.8 / 200 = 0.004 delta; accept 0.6 +- 0.02 (5 SE). Starting at 0.5 with delta 0.001, at
  // most 100 steps never reach a bound.
  auto schedule = Build(Config("continuous_incrementer",
                               {{"delta", 0.001}, {"episode_direction", std::string("up")}}),
                        0, 1, 3);
  double total = 0;
  int steps = 0;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 101);
    for (int k = 2; k <= 101; ++k) {
      EXPECT_NEAR(std::abs(v[k] - v[k - 1]), 0.001, 1e-12);
      total += v[k] - v[k - 1];
      ++steps;
    }
  }
  EXPECT_NEAR(total / steps / 0.001, 0.6, 0.02);
}

TEST(ScheduleContinuousIncrementerTest, RandomEpisodeDirectionIsFiftyFifty) {
  // Builder default episode_direction random. With follow 1, an episode drifts one way only.
  // Of 400 episodes the number going up is Binomial(400, 1/2): 200 +- 50 (5 sd).
  auto schedule = Build(Config("continuous_incrementer",
                               {{"delta", 0.001}, {"follow_predefined_prob", 1.0}}),
                        0, 1, 5);
  int up = 0;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 10);
    ASSERT_NE(v[10], 0.5);
    if (v[10] > 0.5) ++up;
  }
  EXPECT_THAT(up, AllOf(Ge(150), Le(250)));
}

TEST(ScheduleContinuousIncrementerTest, BothWithClipAndNoEpisodeDirectionIsAPlusMinusWalk) {
  // Direction both, edge clip, no episode direction: a new sign every call.
  // Mean step (2 * 0.5 - 1) delta = 0; of 4000 steps the number of up steps is
  // Binomial(4000, 1/2): 2000 +- 158 (5 sd = 5 * 31.6).
  auto schedule = Build(Config("continuous_incrementer",
                               {{"delta", 0.001},
                                {"edge_mode", std::string("clip")},
                                {"episode_direction", std::string("none")},
                                {"follow_predefined_prob", 1.0}}),
                        0, 1, 9);
  int up = 0;
  for (uint64_t episode = 0; episode < 40; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 101);
    for (int k = 2; k <= 101; ++k) up += v[k] > v[k - 1] ? 1 : 0;
  }
  EXPECT_THAT(up, AllOf(Ge(1842), Le(2158)));
}

// ---------------------------------------------------------------------------------------------
// Sudden jump

TEST(ScheduleSuddenJumpTest, JumpsOnlyAtIntervalTimesWithMagnitudesInRange) {
  auto schedule = Build(Config("sudden_jump", {{"step_size_range", std::vector<double>{0.05, 0.1}},
                                               {"interval_range", std::vector<double>{5, 8}}}),
                        0, 10, 13);
  std::map<int, int> first_jump_counts;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    SCOPED_TRACE(episode);
    const std::vector<double> v = RunEpisode(*schedule, 5.0, {.episode = episode}, 200);
    const std::vector<int> jumps = ChangeCalls(v);
    // 200 calls with gaps of at most 8: at least 200 / 8 = 25 jumps, at most 200 / 5 = 40.
    ASSERT_THAT(jumps.size(), AllOf(Ge(24u), Le(40u)));
    EXPECT_THAT(jumps[0], AllOf(Ge(5), Le(8)));
    ++first_jump_counts[jumps[0]];
    for (size_t i = 1; i < jumps.size(); ++i) {
      EXPECT_THAT(jumps[i] - jumps[i - 1], AllOf(Ge(5), Le(8)));
    }
    for (int k : jumps) {
      // Centred at 5 with at most 40 jumps of at most 0.1: never clipped, so the change is the
      // jump itself.
      EXPECT_THAT(std::abs(v[k] - v[k - 1]), AllOf(Ge(0.05 - 1e-12), Le(0.1 + 1e-12)));
    }
  }
  // The first jump is U{5..8}: each time has 100 expected of 400, sd sqrt(400 * .25 * .75) =
  // 8.7; accept 100 +- 43 (5 sd).
  ASSERT_EQ(first_jump_counts.size(), 4u);
  for (const auto& [k, count] : first_jump_counts) {
    EXPECT_THAT(count, AllOf(Ge(57), Le(143))) << k;
  }
}

TEST(ScheduleSuddenJumpTest, SkippedCallsCatchUpEveryDueJump) {
  // The reference's "while k >= next_jump". Interval 10 exactly, direction positive: calling k =
  // 100 right after the reset makes all ten jumps due by then, each in [0.05, 0.1].
  auto schedule = Build(Config("sudden_jump", {{"step_size_range", std::vector<double>{0.05, 0.1}},
                                               {"interval_range", std::vector<double>{10, 10}},
                                               {"direction", std::string("positive")}}),
                        0, 10);
  EXPECT_DOUBLE_EQ(schedule->Reset(1.0, {}), 1.0);
  const double v = schedule->Next(100, 1.0);
  EXPECT_THAT(v - 1.0, AllOf(Ge(0.5 - 1e-12), Le(1.0 + 1e-12)));
  // The next jump is due at 110.
  for (int k = 101; k < 110; ++k) EXPECT_DOUBLE_EQ(schedule->Next(k, v), v) << k;
  EXPECT_GT(schedule->Next(110, v), v);
}

TEST(ScheduleSuddenJumpTest, ValuesStayInBoundsAndClip) {
  // Jumps of 0.3..0.5 on [0, 1] with the builder's default direction both: many are clipped.
  auto schedule = Build(Config("sudden_jump",
                               {{"step_size_frac_range", std::vector<double>{0.3, 0.5}},
                                {"interval_range", std::vector<double>{1, 3}}}),
                        0, 1, 17);
  int at_bound = 0;
  for (uint64_t episode = 0; episode < 50; ++episode) {
    for (double value : RunEpisode(*schedule, 0.5, {.episode = episode}, 100)) {
      ASSERT_THAT(value, AllOf(Ge(0.0), Le(1.0)));
      if (value == 0.0 || value == 1.0) ++at_bound;
    }
  }
  EXPECT_GT(at_bound, 0);  // clipping did happen
}

// ---------------------------------------------------------------------------------------------
// Random walk

TEST(ScheduleRandomWalkTest, FirstCallSkipThenGaussianStepsOfTheGivenStd) {
  // std_frac 0.005 of span 20 = 0.1. 200 episodes x 100 steps = 20000 increments; the sample
  // sd has standard error ~ sd / sqrt(2n) = 0.1 / 200 = 0.0005: accept 0.1 +- 0.0025 (5 SE).
  // The mean step is 0 +- 5 * 0.1 / sqrt(20000) = 0.0035. From 10 on [0, 20], 100 steps of
  // sd 0.1 never reach a bound (10 = 10 sd of the sum).
  auto schedule = Build(Config("random_walk", {{"std_frac", 0.005}}), 0, 20, 21);
  std::vector<double> steps;
  for (uint64_t episode = 0; episode < 200; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 10.0, {.episode = episode}, 101);
    ASSERT_DOUBLE_EQ(v[1], 10.0);  // first-call skip
    for (int k = 2; k <= 101; ++k) steps.push_back(v[k] - v[k - 1]);
  }
  EXPECT_NEAR(StdDev(steps), 0.1, 0.0025);
  EXPECT_NEAR(Mean(steps), 0.0, 0.0035);
  // Gaussian tails: |step| > 2 sd has probability 0.0455; of 20000, 910 +- 5 * 29.5.
  const auto beyond_2sd = std::count_if(steps.begin(), steps.end(),
                                        [](double s) { return std::abs(s) > 0.2; });
  EXPECT_THAT(beyond_2sd, AllOf(Ge(763), Le(1057)));
}

TEST(ScheduleRandomWalkTest, ClipsToTheBounds) {
  auto schedule = Build(Config("random_walk", {{"std", 0.3}}), 0, 1, 23);
  int at_bound = 0;
  for (uint64_t episode = 0; episode < 20; ++episode) {
    for (double value : RunEpisode(*schedule, 0.5, {.episode = episode}, 100)) {
      ASSERT_THAT(value, AllOf(Ge(0.0), Le(1.0)));
      if (value == 0.0 || value == 1.0) ++at_bound;
    }
  }
  EXPECT_GT(at_bound, 0);
}

// ---------------------------------------------------------------------------------------------
// Ornstein-Uhlenbeck

TEST(ScheduleOrnsteinUhlenbeckTest, DeterministicUpdateWithoutNoise) {
  // sigma 0: x' = x + theta (mu - x) exactly. mu defaults to the midpoint 5 of [0, 10].
  auto schedule = Build(Config("ornstein_uhlenbeck", {{"theta", 0.5}, {"sigma", 0.0}}), 0, 10);
  const std::vector<double> v = RunEpisode(*schedule, 1.0, {}, 4);
  EXPECT_DOUBLE_EQ(v[1], 1.0);  // first-call skip
  EXPECT_DOUBLE_EQ(v[2], 3.0);
  EXPECT_DOUBLE_EQ(v[3], 4.0);
  EXPECT_DOUBLE_EQ(v[4], 4.5);
}

TEST(ScheduleOrnsteinUhlenbeckTest, RevertsToMuAtTheRightRate) {
  // theta 0.1, sigma 0.01 * 10 = 0.1, mu = midpoint 5, from 1. After n updates (call n + 1)
  // E[x] = mu + (x0 - mu)(1 - theta)^n. The sd of x_n is at most the stationary
  // sigma / sqrt(1 - (1 - theta)^2) = 0.229; over 400 episodes the standard error of the mean is
  // 0.0115: accept +- 0.06 (5 SE). Values stay several sd away from the bounds (no clipping).
  auto schedule =
      Build(Config("ornstein_uhlenbeck", {{"theta", 0.1}, {"sigma_frac", 0.01}}), 0, 10, 29);
  std::map<int, std::vector<double>> at;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 1.0, {.episode = episode}, 301);
    for (int n : {5, 10, 30, 300}) at[n].push_back(v[n + 1]);
  }
  for (int n : {5, 10, 30, 300}) {
    EXPECT_NEAR(Mean(at[n]), 5.0 - 4.0 * std::pow(0.9, n), 0.06) << n;
  }
  // Long run: the stationary sd 0.229 (+- 10% over 400 samples, SE of an sd ~ 3.5%).
  EXPECT_NEAR(StdDev(at[300]), 0.1 / std::sqrt(1 - 0.81), 0.04);
}

TEST(ScheduleOrnsteinUhlenbeckTest, MuInitialRevertsToTheEpisodeInitialValue) {
  // The paper's variant. From 2 with mu = 2 the mean stays 2, not the midpoint 5; after one
  // update of theta 0.5 from a displaced value it moves halfway back to 2.
  auto noisy = Build(Config("ornstein_uhlenbeck", {{"theta", 0.1},
                                                   {"sigma", 0.1},
                                                   {"mu", std::string("initial")}}),
                     0, 10, 31);
  std::vector<double> at_50;
  for (uint64_t episode = 0; episode < 400; ++episode) {
    at_50.push_back(RunEpisode(*noisy, 2.0, {.episode = episode}, 51)[51]);
  }
  EXPECT_NEAR(Mean(at_50), 2.0, 0.06);  // 5 SE, as above

  auto exact = Build(Config("ornstein_uhlenbeck",
                            {{"theta", 0.5}, {"sigma", 0.0}, {"mu", std::string("initial")}}),
                     0, 10);
  exact->Reset(2.0, {});
  EXPECT_DOUBLE_EQ(exact->Next(1, 6.0), 6.0);  // skip
  EXPECT_DOUBLE_EQ(exact->Next(2, 6.0), 4.0);
}

TEST(ScheduleOrnsteinUhlenbeckTest, MuFracAndAbsoluteMu) {
  auto frac = Build(Config("ornstein_uhlenbeck",
                           {{"theta", 1.0}, {"sigma", 0.0}, {"mu_frac", 0.25}}),
                    2, 6);
  EXPECT_DOUBLE_EQ(RunEpisode(*frac, 5.0, {}, 2)[2], 3.0);  // theta 1 snaps to 2 + 0.25 * 4
  auto absolute = Build(Config("ornstein_uhlenbeck",
                               {{"theta", 1.0}, {"sigma", 0.0}, {"mu", 5.5}}),
                        2, 6);
  EXPECT_DOUBLE_EQ(RunEpisode(*absolute, 3.0, {}, 2)[2], 5.5);
}

// ---------------------------------------------------------------------------------------------
// Piecewise constant

TEST(SchedulePiecewiseConstantTest, KeepsInitialValueUntilFirstSwitchThenListValues) {
  const std::vector<double> levels = {0.2, 0.4, 0.6, 0.8};
  auto schedule = Build(Config("piecewise_constant",
                               {{"values", levels},
                                {"interval_range", std::vector<double>{5, 10}}}),
                        0, 1, 37);
  std::map<double, int> level_counts;
  for (uint64_t episode = 0; episode < 200; ++episode) {
    SCOPED_TRACE(episode);
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 100);
    const std::vector<int> changes = ChangeCalls(v);
    ASSERT_FALSE(changes.empty());
    // 0.5 is not in the list, so the first switch is the first change: at U{5..10}.
    EXPECT_THAT(changes[0], AllOf(Ge(5), Le(10)));
    for (int k = 0; k < changes[0]; ++k) EXPECT_DOUBLE_EQ(v[k], 0.5);
    for (int k = changes[0]; k <= 100; ++k) {
      EXPECT_TRUE(std::count(levels.begin(), levels.end(), v[k]) == 1) << v[k];
    }
    // Switches are at least 5 calls apart (a switch may repeat the level, so changes are
    // sums of intervals: gaps >= 5).
    for (size_t i = 1; i < changes.size(); ++i) EXPECT_GE(changes[i] - changes[i - 1], 5);
    for (int k : changes) ++level_counts[v[k]];
  }
  // Every level occurs.
  EXPECT_EQ(level_counts.size(), levels.size());
}

TEST(SchedulePiecewiseConstantTest, AtMostOneSwitchPerCall) {
  // Interval 10 exactly. Jumping to k = 1000 makes many switches overdue, but a call makes one
  // switch only and adds one interval, so the next calls keep switching (a level is drawn
  // again at every one of them: with four levels, eight calls without a change have
  // probability (1/4)^8). A "while" loop would instead catch up and stay constant until 1010.
  auto schedule = Build(Config("piecewise_constant",
                               {{"values", std::vector<double>{0.2, 0.4, 0.6, 0.8}},
                                {"interval_range", std::vector<double>{10, 10}}}),
                        0, 1, 41);
  double v = schedule->Reset(0.5, {});
  v = schedule->Next(1000, v);
  int changes = 0;
  for (int k = 1001; k <= 1008; ++k) {
    const double next = schedule->Next(k, v);
    if (next != v) ++changes;
    v = next;
  }
  EXPECT_GT(changes, 0);
}

// ---------------------------------------------------------------------------------------------
// Sinusoidal jump

TEST(ScheduleSinusoidalJumpTest, WithoutJumpsItIsTheSinusoid) {
  // The first jump is due at call 1000: over 100 calls only the sinusoid (random direction).
  const double w = 2 * std::numbers::pi / 20;
  auto schedule = Build(Config("sinusoidal_jump",
                               {{"amplitude", 0.1},
                                {"period", 20.0},
                                {"interval_range", std::vector<double>{1000, 1000}}}),
                        0, 1, 43);
  std::set<double> first_moves;
  for (uint64_t episode = 0; episode < 20; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 100);
    const double dir = v[1] < 0.5 ? 1.0 : -1.0;
    first_moves.insert(dir);
    for (int k = 1; k <= 100; ++k) {
      EXPECT_NEAR(v[k], 0.5 - 0.1 * std::sin(dir * w * k), 1e-12) << k;
    }
  }
  EXPECT_EQ(first_moves.size(), 2u);  // both directions occur (p = 2^-19 otherwise)
}

TEST(ScheduleSinusoidalJumpTest, BaselineJumpsAtIntervalTimes) {
  // Amplitude 0: the value is the baseline, which jumps by +-U(0.05, 0.1) at U{5..8}.
  auto schedule = Build(Config("sinusoidal_jump",
                               {{"amplitude", 0.0},
                                {"step_size_range", std::vector<double>{0.05, 0.1}},
                                {"interval_range", std::vector<double>{5, 8}}}),
                        0, 10, 47);
  for (uint64_t episode = 0; episode < 50; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 5.0, {.episode = episode}, 100);
    const std::vector<int> jumps = ChangeCalls(v);
    ASSERT_GE(jumps.size(), 12u);  // 100 / 8
    EXPECT_THAT(jumps[0], AllOf(Ge(5), Le(8)));
    for (size_t i = 1; i < jumps.size(); ++i) {
      EXPECT_THAT(jumps[i] - jumps[i - 1], AllOf(Ge(5), Le(8)));
    }
    for (int k : jumps) {
      EXPECT_THAT(std::abs(v[k] - v[k - 1]), AllOf(Ge(0.05 - 1e-12), Le(0.1 + 1e-12)));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Phased OU

TEST(SchedulePhasedOuTest, TargetsComeFromValuesAndSwitchAtIntervalTimes) {
  // theta 1, sigma 0: every update snaps to the current target, so the value is the target
  // (up to rounding: x + 1 * (mu - x)).
  const std::vector<double> targets = {0.2, 0.8};
  auto schedule = Build(Config("phased_ou", {{"theta", 1.0},
                                             {"sigma", 0.0},
                                             {"values", targets},
                                             {"interval_range", std::vector<double>{10, 20}}}),
                        0, 1, 53);
  std::set<double> seen;
  for (uint64_t episode = 0; episode < 100; ++episode) {
    SCOPED_TRACE(episode);
    const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 200);
    EXPECT_DOUBLE_EQ(v[1], 0.5);  // first-call skip
    for (int k = 2; k <= 200; ++k) {
      const double target = std::abs(v[k] - 0.2) < 1e-12 ? 0.2 : 0.8;
      ASSERT_NEAR(v[k], target, 1e-12) << k;
      seen.insert(target);
    }
    // Changes after the first update are retargets, at least 10 calls apart; the first is due
    // at U{10..20}, so no change happens before call 10.
    const std::vector<int> changes = MoveCalls(v, 1e-9);
    for (size_t i = 1; i < changes.size(); ++i) {
      EXPECT_GE(changes[i], 10);
      if (i >= 2) {
        EXPECT_GE(changes[i] - changes[i - 1], 10);
      }
    }
  }
  EXPECT_EQ(seen.size(), 2u);
}

TEST(SchedulePhasedOuTest, DefaultTargetsAreMinMidMax) {
  auto schedule = Build(Config("phased_ou", {{"theta", 1.0}, {"sigma", 0.0}}), 1, 3, 59);
  std::set<double> seen;  // values rounded to 1e-9 (theta 1 snaps up to rounding)
  for (uint64_t episode = 0; episode < 60; ++episode) {
    for (double value : RunEpisode(*schedule, 1.7, {.episode = episode}, 400)) {
      seen.insert(std::round(value * 1e9) / 1e9);
    }
  }
  EXPECT_EQ(seen, (std::set<double>{1.0, 1.7, 2.0, 3.0}));  // 1.7: the initial value
}

// ---------------------------------------------------------------------------------------------
// Levy walk, sequential, identity

TEST(ScheduleLevyWalkTest, IsASuddenJumpFollowedByARandomWalk) {
  // The reference's make_levy_walk: Sequential([SuddenJump(both, 0.5, clip), RandomWalk]) with
  // seeds spawned from the Levy walk's seed, which is exactly what a sequential config of those
  // two parts with the same seed is.
  const Params jump = {{"step_size_range", std::vector<double>{0.2, 0.3}},
                       {"interval_range", std::vector<double>{5, 9}}};
  ScheduleConfig levy = Config("levy_walk", {{"std", 0.01},
                                             {"step_size_range", std::vector<double>{0.2, 0.3}},
                                             {"interval_range", std::vector<double>{5, 9}}});
  ScheduleConfig sequential = Config("sequential");
  sequential.parts = {Config("sudden_jump", jump), Config("random_walk", {{"std", 0.01}})};
  auto a = Build(levy, -2, 2, 61);
  auto b = Build(sequential, -2, 2, 61);
  for (uint64_t episode = 0; episode < 5; ++episode) {
    EXPECT_EQ(RunEpisode(*a, 0.1, {.episode = episode, .slot = 2}, 100),
              RunEpisode(*b, 0.1, {.episode = episode, .slot = 2}, 100));
  }
}

TEST(ScheduleLevyWalkTest, JumpsAtIntervalTimesAndNoiseOtherwise) {
  // Jumps of 0.5..0.6 at U{10..12}; noise sd 0.001 in between (first call: no noise, skip).
  auto schedule = Build(Config("levy_walk", {{"std", 0.001},
                                             {"step_size_range", std::vector<double>{0.5, 0.6}},
                                             {"interval_range", std::vector<double>{10, 12}}}),
                        -10, 10, 67);
  for (uint64_t episode = 0; episode < 30; ++episode) {
    const std::vector<double> v = RunEpisode(*schedule, 0.0, {.episode = episode}, 100);
    std::vector<int> big;
    for (int k = 1; k <= 100; ++k) {
      const double change = std::abs(v[k] - v[k - 1]);
      if (change > 0.1) {
        big.push_back(k);
        // A jump plus one noise step (|noise| < 0.01 = 10 sd).
        EXPECT_THAT(change, AllOf(Ge(0.49), Le(0.61)));
      } else {
        EXPECT_LT(change, 0.01);  // 10 sd of the noise
        if (k == 1) {
          EXPECT_EQ(change, 0.0);  // the random-walk part's first-call skip (no jump due yet)
        } else {
          EXPECT_GT(change, 0.0);  // the random walk moves every call after the first
        }
      }
    }
    ASSERT_FALSE(big.empty());
    EXPECT_THAT(big[0], AllOf(Ge(10), Le(12)));
    for (size_t i = 1; i < big.size(); ++i) {
      EXPECT_THAT(big[i] - big[i - 1], AllOf(Ge(10), Le(12)));
    }
  }
}

TEST(ScheduleSequentialTest, AppliesPartsInOrder) {
  // Part 1 sets 0.9 at every call (interval 1); part 2 steps down by 0.1 (after its skip).
  // In this order call k >= 2 gives 0.8; in the other order the level overwrites the step.
  const ScheduleConfig level = Config("piecewise_constant",
                                      {{"values", std::vector<double>{0.9}},
                                       {"interval_range", std::vector<double>{1, 1}}});
  const ScheduleConfig step = Config("continuous_incrementer",
                                     {{"delta", 0.1},
                                      {"episode_direction", std::string("down")},
                                      {"follow_predefined_prob", 1.0}});
  ScheduleConfig level_then_step = Config("sequential");
  level_then_step.parts = {level, step};
  ScheduleConfig step_then_level = Config("sequential");
  step_then_level.parts = {step, level};
  auto a = Build(level_then_step, 0, 1);
  auto b = Build(step_then_level, 0, 1);
  const std::vector<double> va = RunEpisode(*a, 0.5, {}, 5);
  const std::vector<double> vb = RunEpisode(*b, 0.5, {}, 5);
  EXPECT_DOUBLE_EQ(va[1], 0.9);  // the step part skips its first call
  for (int k = 2; k <= 5; ++k) {
    EXPECT_NEAR(va[k], 0.8, 1e-12) << k;
    EXPECT_DOUBLE_EQ(vb[k], 0.9) << k;
  }
}

TEST(ScheduleIdentityTest, KeepsTheValue) {
  for (const char* name : {"identity", "constant"}) {
    auto schedule = Build(Config(name), 0, 1);
    const std::vector<double> v = RunEpisode(*schedule, 0.37, {.episode = 4, .slot = 1}, 500);
    for (double value : v) EXPECT_DOUBLE_EQ(value, 0.37) << name;
    // Reset clips; Next returns the current value unchanged.
    EXPECT_DOUBLE_EQ(schedule->Reset(1.5, {}), 1.0);
    EXPECT_DOUBLE_EQ(schedule->Next(3, 0.25), 0.25);
  }
}

// ---------------------------------------------------------------------------------------------
// Determinism and bounds, every family

// A configuration of every stochastic family with visible randomness in 100 calls.
std::vector<ScheduleConfig> StochasticConfigs() {
  ScheduleConfig sequential = Config("sequential");
  sequential.parts = {Config("random_walk", {{"std_frac", 0.02}}),
                      Config("sudden_jump", {{"interval_range", std::vector<double>{5, 10}}})};
  return {
      Config("continuous_incrementer", {{"delta_frac", 0.01}}),
      Config("sudden_jump", {{"interval_range", std::vector<double>{5, 10}}}),
      Config("random_walk", {{"std_frac", 0.02}}),
      Config("ornstein_uhlenbeck", {{"sigma_frac", 0.02}}),
      Config("piecewise_constant", {{"values", std::vector<double>{0, 0.1, 0.2, 0.3, 0.4, 0.5}},
                                    {"interval_range", std::vector<double>{3, 7}}}),
      Config("sinusoidal_jump", {{"interval_range", std::vector<double>{5, 10}}}),
      Config("phased_ou", {{"interval_range", std::vector<double>{5, 10}}}),
      Config("levy_walk", {{"interval_range", std::vector<double>{5, 10}}}),
      sequential,
  };
}

TEST(ScheduleDeterminismTest, SameSeedEpisodeAndSlotGiveTheSameTrajectory) {
  for (const ScheduleConfig& config : StochasticConfigs()) {
    SCOPED_TRACE(config.family);
    auto a = Build(config, 0, 0.5, 101);
    auto b = Build(config, 0, 0.5, 101);
    const EpisodeId id = {.episode = 12, .slot = 3};
    const std::vector<double> reference = RunEpisode(*a, 0.25, id, 100);
    EXPECT_EQ(RunEpisode(*b, 0.25, id, 100), reference);
    // Another episode, another slot, another seed: another trajectory.
    EXPECT_NE(RunEpisode(*b, 0.25, {.episode = 13, .slot = 3}, 100), reference);
    EXPECT_NE(RunEpisode(*b, 0.25, {.episode = 12, .slot = 4}, 100), reference);
    EXPECT_NE(RunEpisode(*Build(config, 0, 0.5, 102), 0.25, id, 100), reference);
  }
}

TEST(ScheduleDeterminismTest, ResetRestartsTheGenerator) {
  // An episode's trajectory depends on (seed, episode, slot) only, not on earlier episodes.
  for (const ScheduleConfig& config : StochasticConfigs()) {
    SCOPED_TRACE(config.family);
    auto used = Build(config, 0, 0.5, 103);
    const std::vector<double> first = RunEpisode(*used, 0.25, {.episode = 0}, 100);
    const std::vector<double> second = RunEpisode(*used, 0.25, {.episode = 1}, 150);
    EXPECT_EQ(RunEpisode(*used, 0.25, {.episode = 0}, 100), first);
    auto fresh = Build(config, 0, 0.5, 103);
    EXPECT_EQ(RunEpisode(*fresh, 0.25, {.episode = 1}, 150), second);
    // Stopping an episode early does not shift the next one.
    RunEpisode(*fresh, 0.25, {.episode = 0}, 3);
    EXPECT_EQ(RunEpisode(*fresh, 0.25, {.episode = 1}, 150), second);
  }
}

TEST(ScheduleDeterminismTest, RandomDirectionFamiliesDifferAcrossEpisodes) {
  // Sinusoidal and cosine (direction random) draw one bit per episode: over 20 episodes both
  // outcomes occur (probability 2^-19 otherwise), and a repeated episode repeats its outcome.
  for (const ScheduleConfig& config :
       {Config("sinusoidal", {{"amplitude_frac", 0.2}, {"period", 30.0}}),
        Config("cosine_annealing", {{"T_0", 30.0}, {"direction", std::string("random")}})}) {
    SCOPED_TRACE(config.family);
    auto schedule = Build(config, 0, 1, 107);
    std::set<std::vector<double>> trajectories;
    for (uint64_t episode = 0; episode < 20; ++episode) {
      const std::vector<double> v = RunEpisode(*schedule, 0.5, {.episode = episode}, 20);
      EXPECT_EQ(RunEpisode(*schedule, 0.5, {.episode = episode}, 20), v);
      trajectories.insert(v);
    }
    EXPECT_EQ(trajectories.size(), 2u);
  }
}

// A random configuration of `family` on [lo, hi] with aggressive magnitudes (up to several
// spans), so that bounds handling is exercised.
ScheduleConfig RandomConfig(const std::string& family, Random& random) {
  auto frac = [&random](double hi) { return random.Uniform(0, hi); };
  auto interval = [&random]() {
    const double lo = static_cast<double>(random.Integers(1, 10));
    return std::vector<double>{lo, lo + static_cast<double>(random.Integers(0, 10))};
  };
  auto frac_range = [&random](double hi) {
    const double lo = random.Uniform(0, hi);
    return std::vector<double>{lo, lo + random.Uniform(0, hi)};
  };
  if (family == "sinusoidal") {
    return Config(family, {{"amplitude_frac", frac(3)}, {"period", 1 + frac(59)}});
  }
  if (family == "cosine_annealing") {
    const char* retarget[] = {"swap", "restart", "random"};
    const char* direction[] = {"auto", "to_min", "to_max", "random"};
    return Config(family, {{"T_0", static_cast<double>(random.Integers(1, 40))},
                           {"T_mult", static_cast<double>(random.Integers(1, 3))},
                           {"neighborhood_radius_frac", frac(1.5)},
                           {"min_delta", frac(0.5)},
                           {"retarget", std::string(retarget[random.Integers(0, 3)])},
                           {"direction", std::string(direction[random.Integers(0, 4)])}});
  }
  if (family == "continuous_incrementer") {
    const char* edge[] = {"clip", "reflect"};
    const char* episode[] = {"none", "up", "down", "random"};
    const char* direction[] = {"positive", "negative", "both"};
    return Config(family, {{"delta_frac", frac(0.5)},
                           {"noise_std", frac(0.2)},
                           {"edge_mode", std::string(edge[random.Integers(0, 2)])},
                           {"episode_direction", std::string(episode[random.Integers(0, 4)])},
                           {"direction", std::string(direction[random.Integers(0, 3)])}});
  }
  if (family == "random_walk") return Config(family, {{"std_frac", frac(0.5)}});
  if (family == "sudden_jump") {
    const char* edge[] = {"clip", "reflect"};
    return Config(family, {{"step_size_frac_range", frac_range(1.5)},
                           {"interval_range", interval()},
                           {"edge_mode", std::string(edge[random.Integers(0, 2)])}});
  }
  if (family == "ornstein_uhlenbeck") {
    return Config(family, {{"theta", frac(1)}, {"sigma_frac", frac(1)}, {"mu_frac", frac(1)}});
  }
  if (family == "piecewise_constant") {
    return Config(family,
                  {{"values", std::vector<double>{0.0, 0.5}}, {"interval_range", interval()}});
  }
  if (family == "sinusoidal_jump") {
    return Config(family, {{"amplitude_frac", frac(3)},
                           {"period", 1 + frac(59)},
                           {"step_size_frac_range", frac_range(1.5)},
                           {"interval_range", interval()}});
  }
  if (family == "phased_ou") {
    return Config(family,
                  {{"theta", frac(1)}, {"sigma_frac", frac(1)}, {"interval_range", interval()}});
  }
  if (family == "levy_walk") {
    return Config(family, {{"std_frac", frac(0.5)},
                           {"step_size_frac_range", frac_range(1.5)},
                           {"interval_range", interval()}});
  }
  if (family == "sequential") {
    ScheduleConfig config = Config(family);
    config.parts = {RandomConfig("sinusoidal", random), RandomConfig("sudden_jump", random)};
    return config;
  }
  return Config(family);
}

TEST(ScheduleBoundsTest, EveryFamilyStaysWithinBounds) {
  // 20 random configs per family, each with its own random bounds (piecewise levels are then
  // set to {lo, mid, hi} so that they lie within them), 5 episodes of 300 calls each.
  Random random(uint64_t{2026});
  for (const std::string& family : ScheduleFamilyNames()) {
    SCOPED_TRACE(family);
    for (int trial = 0; trial < 20; ++trial) {
      const double lo = random.Uniform(-5, 5);
      const double hi = lo + random.Uniform(0.1, 10);
      ScheduleConfig config = RandomConfig(family, random);
      if (family == "piecewise_constant") {
        config.params["values"] = std::vector<double>{lo, 0.5 * (lo + hi), hi};
      }
      absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, lo, hi, 1000 + trial);
      ASSERT_TRUE(spec.ok()) << spec.status();
      auto schedule = MakeSchedule(*spec);
      for (uint64_t episode = 0; episode < 5; ++episode) {
        const double initial = random.Uniform(lo, hi);
        for (double value : RunEpisode(*schedule, initial, {.episode = episode, .slot = 1}, 300)) {
          ASSERT_THAT(value, AllOf(Ge(lo), Le(hi))) << "trial " << trial;
        }
      }
    }
  }
}

TEST(ScheduleBoundsTest, ResetClipsAnInitialValueOutsideTheBounds) {
  // Every family's Reset returns the episode-initial value clipped to the bounds.
  for (const std::string& family : ScheduleFamilyNames()) {
    SCOPED_TRACE(family);
    Random random(uint64_t{5});
    ScheduleConfig config = RandomConfig(family, random);
    if (family == "piecewise_constant") config.params["values"] = std::vector<double>{2.0};
    auto schedule = Build(config, 1, 3);
    EXPECT_DOUBLE_EQ(schedule->Reset(7.0, {}), 3.0);
    EXPECT_DOUBLE_EQ(schedule->Reset(-7.0, {}), 1.0);
  }
}

}  // namespace
}  // namespace dcs::env
