// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_SCHEDULE_INTERNAL_H_
#define DCS_ENV_SCHEDULE_INTERNAL_H_

// Building blocks shared by the schedule families (schedule_*.cc); not for use outside env/.

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>

#include "common/random.h"
#include "env/schedule.h"

namespace dcs::env::internal {

// What every family has: bounds, and a generator restarted at every episode.
class BoundedSchedule : public Schedule {
 protected:
  explicit BoundedSchedule(const ScheduleSpec& spec)
      : min_(spec.min_value), max_(spec.max_value), seed_(spec.seed) {}

  double Clip(double value) const { return std::clamp(value, min_, max_); }

  // Reflects a value that crossed a bound back about that bound (once; callers clip after).
  double Reflect(double value) const {
    if (value < min_) return 2 * min_ - value;
    if (value > max_) return 2 * max_ - value;
    return value;
  }

  // The reference's per-episode generator: SeedSequence([seed, episode, slot]).
  void StartEpisode(EpisodeId id) { random_ = EpisodeRandom(seed_, id.episode, id.slot); }

  // An interval draw U{lo..hi}.
  int64_t DrawInterval(StepRange range) { return random_.Integers(range.lo, range.hi + 1); }

  // +1 with probability `p_positive`, else -1.
  double DrawSign(double p_positive) { return random_.Bernoulli(p_positive) ? 1.0 : -1.0; }

  // The sign a Direction prescribes (kBoth: drawn).
  double DirectionSign(Direction direction, double p_positive) {
    switch (direction) {
      case Direction::kPositive: return 1.0;
      case Direction::kNegative: return -1.0;
      case Direction::kBoth: return DrawSign(p_positive);
    }
    return 1.0;
  }

  const double min_;
  const double max_;
  const uint32_t seed_;
  Random random_{0};
};

// Families whose first call after a reset changes nothing (the reference's first-call skip:
// ContinuousIncrementer, RandomWalk, Ornstein-Uhlenbeck, Phased OU).
class SkipFirstCall {
 public:
  void Arm() { skip_ = true; }
  // True once per episode, on the first call.
  bool Consume() { return std::exchange(skip_, false); }

 private:
  bool skip_ = true;
};

// The base seed of part `child` of a composite schedule seeded with `seed`: numpy's
// SeedSequence(seed).spawn(n)[child].generate_state(1)[0], as the reference's Levy walk does.
uint32_t SpawnSeed(uint32_t seed, uint32_t child);

std::unique_ptr<Schedule> MakeContinuousIncrementer(const ScheduleSpec& spec,
                                                    const ContinuousIncrementerParams& params);
std::unique_ptr<Schedule> MakeSuddenJump(const ScheduleSpec& spec, const SuddenJumpParams& params);
std::unique_ptr<Schedule> MakeRandomWalk(const ScheduleSpec& spec, const RandomWalkParams& params);
std::unique_ptr<Schedule> MakeOrnsteinUhlenbeck(const ScheduleSpec& spec,
                                                const OrnsteinUhlenbeckParams& params);
std::unique_ptr<Schedule> MakePiecewiseConstant(const ScheduleSpec& spec,
                                                const PiecewiseConstantParams& params);
std::unique_ptr<Schedule> MakeSinusoidal(const ScheduleSpec& spec, const SinusoidalParams& params);
std::unique_ptr<Schedule> MakeCosineAnnealing(const ScheduleSpec& spec,
                                              const CosineAnnealingParams& params);
std::unique_ptr<Schedule> MakeSinusoidalJump(const ScheduleSpec& spec,
                                             const SinusoidalJumpParams& params);
std::unique_ptr<Schedule> MakePhasedOu(const ScheduleSpec& spec, const PhasedOuParams& params);

}  // namespace dcs::env::internal

#endif  // DCS_ENV_SCHEDULE_INTERNAL_H_
