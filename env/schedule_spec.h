// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_SCHEDULE_SPEC_H_
#define DCS_ENV_SCHEDULE_SPEC_H_

// A schedule's specification: plain data that says how one context feature moves within an
// episode. The families and their rules are those of the reference implementation
// (dynamicCARL, docs/reference.md, "Schedule families"), with the paper's names. Every magnitude
// here is in the feature's absolute units and every interval or period in environment steps;
// env/schedule_config.h builds a spec from a config that may give magnitudes as fractions of the
// range instead. The state machine that runs a spec is env/schedule.h.
//
// Field defaults are those of the reference factories (make_sinusoidal, ...) where they have
// one; configs get the builder's defaults instead (env/schedule_config.h).
//
// Thread-safe (immutable data).

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "absl/strings/string_view.h"

namespace dcs::env {

// [lo, hi] of a continuous draw U(lo, hi).
struct Range {
  double lo = 0;
  double hi = 0;
};

// [lo, hi] of an integer draw U{lo..hi}, both ends included (an interval in steps).
struct StepRange {
  int64_t lo = 1;
  int64_t hi = 1;
};

// Which way a step or jump goes.
enum class Direction { kPositive, kNegative, kBoth };
// What happens when a step crosses a bound: clipped, or reflected about the bound and clipped.
enum class EdgeMode { kClip, kReflect };

// 1. The context stays at its episode-initial value: the static baseline.
struct IdentityParams {};

// 2. x += s * delta each step (+ optional Gaussian noise), s a sign fixed per episode or drawn
// per step; reflecting at a bound flips s. First call after reset: no change.
struct ContinuousIncrementerParams {
  enum class EpisodeDirection { kNone, kUp, kDown, kRandom };
  double delta = 0.01;
  Direction direction = Direction::kPositive;
  double direction_prob = 0.5;  // P(s = +1) when direction is kBoth
  EdgeMode edge_mode = EdgeMode::kClip;
  // If not kNone, decides the episode's sign at reset (kRandom: +1 or -1 with probability 1/2).
  EpisodeDirection episode_direction = EpisodeDirection::kNone;
  double noise_std = 0;
  // If set, each step keeps the sign with this probability and reverses it otherwise.
  std::optional<double> follow_predefined_prob;
};

// 3. The paper's "Stochastic Jumps": every U{interval} steps, x += sign * U(step_size).
struct SuddenJumpParams {
  Range step_size = {0.2, 0.4};
  StepRange interval = {10, 30};
  Direction direction = Direction::kBoth;
  double direction_prob = 0.5;
  EdgeMode edge_mode = EdgeMode::kClip;
};

// 4. x += N(0, std) each step. First call after reset: no change.
struct RandomWalkParams {
  double std = 0.01;
};

// 5. x += theta * (mu - x) + N(0, sigma) each step. First call after reset: no change.
struct OrnsteinUhlenbeckParams {
  double theta = 0.1;
  double mu = 0;  // the reversion target, unless mu_is_episode_initial
  // The paper's variant: revert to the episode-initial value instead of `mu`.
  bool mu_is_episode_initial = false;
  double sigma = 0.02;
};

// 6. Held constant; every U{interval} steps a new level drawn uniformly from `values`.
struct PiecewiseConstantParams {
  std::vector<double> values;
  StepRange interval = {30, 50};
};

// 7. x = baseline - amplitude * sin(phase), the phase advancing by 2*pi/period per step in a
// direction that reverses whenever the next value would leave the bounds. The baseline is the
// episode-initial value.
struct SinusoidalParams {
  enum class InitialDirection { kRandom, kDown, kUp };  // which way the value moves first
  double amplitude = 0.1;
  double period = 100;
  InitialDirection initial_direction = InitialDirection::kRandom;
};

// 8. Cosine annealing with warm restarts (SGDR): from a start value to an end value over a
// cycle, value = end + (start - end) * (1 + cos(pi * t / (T - 1))) / 2; in cycle mode a new
// cycle every T_0 * T_mult^i steps, retargeted.
struct CosineAnnealingParams {
  enum class Mode { kOnce, kCycle };
  enum class EndDirection { kAuto, kToMin, kToMax, kRandom };
  enum class Retarget { kSwap, kRestart, kRandom };
  Mode mode = Mode::kOnce;
  std::optional<double> start;  // default: the episode-initial value
  std::optional<double> end;    // mode kOnce only; default: chosen by `direction`
  int64_t t_max = 1000;         // cycle length in mode kOnce
  int64_t t_0 = 200;            // first cycle length in mode kCycle
  int64_t t_mult = 1;           // cycle length growth factor
  // If set (> 0), cycles stay within [centre - r, centre + r] of their start.
  std::optional<double> neighborhood_radius;
  double min_delta = 0;  // smallest |end - start| of a cycle
  EndDirection direction = EndDirection::kAuto;
  Retarget retarget = Retarget::kSwap;
  double repel_edge_eps_frac = 0.05;  // a start this close to a band edge heads for the other
};

// 9. A sinusoid around a baseline that jumps by +-U(step_size) every U{interval} steps.
struct SinusoidalJumpParams {
  double amplitude = 0.1;
  double period = 100;
  Range step_size = {0.2, 0.4};
  StepRange interval = {80, 150};
};

// 10. Ornstein-Uhlenbeck whose target is redrawn from `values` every U{interval} steps.
// First call after reset: no change.
struct PhasedOuParams {
  double theta = 0.05;
  double sigma = 0.02;
  std::vector<double> values;
  StepRange interval = {100, 150};
};

// 11. The paper's "Levy walk", as the reference defines it: a sudden jump (both directions,
// clipped) followed each step by a random-walk step. Not a heavy-tailed sampler.
struct LevyWalkParams {
  double std = 0.01;
  Range step_size = {0.2, 0.4};
  StepRange interval = {40, 80};
};

struct ScheduleSpec;

// 12. Several schedules applied in order each step, each to the value the previous produced.
struct SequentialParams {
  std::vector<ScheduleSpec> parts;
};

enum class ScheduleFamily {
  kIdentity,
  kContinuousIncrementer,
  kSuddenJump,
  kRandomWalk,
  kOrnsteinUhlenbeck,
  kPiecewiseConstant,
  kSinusoidal,
  kCosineAnnealing,
  kSinusoidalJump,
  kPhasedOu,
  kLevyWalk,
  kSequential,
};

// Indexed by ScheduleFamily; each alternative's index is its family.
using ScheduleParams =
    std::variant<IdentityParams, ContinuousIncrementerParams, SuddenJumpParams,
                 RandomWalkParams, OrnsteinUhlenbeckParams, PiecewiseConstantParams,
                 SinusoidalParams, CosineAnnealingParams, SinusoidalJumpParams, PhasedOuParams,
                 LevyWalkParams, SequentialParams>;

struct ScheduleSpec {
  // Every value the schedule produces is clipped to [min_value, max_value] (finite,
  // min_value < max_value): in the paper's experiments, the training range.
  double min_value = 0;
  double max_value = 1;
  // The schedule's base seed; episode e of environment slot s draws from a generator derived
  // from (seed, e, s), the reference's SeedSequence([seed, episode, worker]).
  uint32_t seed = 0;
  ScheduleParams params;

  ScheduleFamily family() const { return static_cast<ScheduleFamily>(params.index()); }
};

// The family's name as configs spell it: "sinusoidal", "ornstein_uhlenbeck", ...
absl::string_view ScheduleFamilyName(ScheduleFamily family);

}  // namespace dcs::env

#endif  // DCS_ENV_SCHEDULE_SPEC_H_
