// Copyright 2026 The DCS Authors.
//
// The periodic families: Sinusoidal, Sinusoidal Jump and Cosine Annealing with warm restarts
// (docs/reference.md, "Schedule families").

#include <cmath>
#include <numbers>

#include "env/schedule_internal.h"

namespace dcs::env::internal {
namespace {

// value = baseline - amplitude * sin(phase); each step the phase moves by omega in the current
// direction, and the direction reverses when the next value would leave [min, max] (the
// reference's reflection of the phase direction).
class PhaseReflectingSine {
 public:
  PhaseReflectingSine(double amplitude, double period)
      : amplitude_(amplitude), omega_(2 * std::numbers::pi / std::max(1.0, period)) {}

  void Start(double direction) {
    phase_ = 0;
    direction_ = direction;
  }

  // The next value around `baseline`, before clipping.
  double Advance(double baseline, double min, double max) {
    double phase = phase_ + direction_ * omega_;
    const double value = baseline - amplitude_ * std::sin(phase);
    if (value < min || value > max) {
      direction_ = -direction_;
      phase = phase_ + direction_ * omega_;
    }
    phase_ = phase;
    return baseline - amplitude_ * std::sin(phase_);
  }

 private:
  const double amplitude_;
  const double omega_;
  double phase_ = 0;
  double direction_ = 1;
};

class Sinusoidal final : public BoundedSchedule {
 public:
  Sinusoidal(const ScheduleSpec& spec, const SinusoidalParams& params)
      : BoundedSchedule(spec),
        initial_direction_(params.initial_direction),
        sine_(params.amplitude, params.period) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    baseline_ = initial;
    using InitialDirection = SinusoidalParams::InitialDirection;
    // A positive phase direction moves the value down first (value = baseline - A sin).
    switch (initial_direction_) {
      case InitialDirection::kRandom: sine_.Start(DrawSign(0.5)); break;
      case InitialDirection::kDown: sine_.Start(1); break;
      case InitialDirection::kUp: sine_.Start(-1); break;
    }
    return Clip(baseline_);
  }

  double Next(int64_t /*k*/, double /*current*/) override {
    return Clip(sine_.Advance(baseline_, min_, max_));
  }

 private:
  const SinusoidalParams::InitialDirection initial_direction_;
  PhaseReflectingSine sine_;
  double baseline_ = 0;
};

class SinusoidalJump final : public BoundedSchedule {
 public:
  SinusoidalJump(const ScheduleSpec& spec, const SinusoidalJumpParams& params)
      : BoundedSchedule(spec), params_(params), sine_(params.amplitude, params.period) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    baseline_ = initial;
    sine_.Start(DrawSign(0.5));
    next_jump_ = DrawInterval(params_.interval);
    return Clip(baseline_);
  }

  double Next(int64_t k, double /*current*/) override {
    if (k >= next_jump_) {
      const double sign = DrawSign(0.5);
      baseline_ = Clip(baseline_ + sign * random_.Uniform(params_.step_size.lo,
                                                          params_.step_size.hi));
      next_jump_ += DrawInterval(params_.interval);
    }
    return Clip(sine_.Advance(baseline_, min_, max_));
  }

 private:
  const SinusoidalJumpParams params_;
  PhaseReflectingSine sine_;
  double baseline_ = 0;
  int64_t next_jump_ = 0;
};

class CosineAnnealing final : public BoundedSchedule {
 public:
  using Params = CosineAnnealingParams;

  CosineAnnealing(const ScheduleSpec& spec, const Params& params)
      : BoundedSchedule(spec), params_(params) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    episode_centre_ = Clip(params_.start.value_or(initial));
    cycle_start_ = 0;
    cycle_length_ = params_.mode == Params::Mode::kOnce ? params_.t_max : params_.t_0;
    StartCycle(episode_centre_, /*retargeted=*/false);
    return Clip(start_);
  }

  double Next(int64_t k, double /*current*/) override {
    if (params_.mode == Params::Mode::kCycle) {
      while (k - cycle_start_ >= cycle_length_) {
        cycle_start_ += cycle_length_;
        cycle_length_ *= params_.t_mult;
        Retarget();
      }
    }
    const int64_t t = k - cycle_start_;
    const double length = static_cast<double>(cycle_length_);
    double value = start_;
    if (cycle_length_ > 1) {
      const double f = std::clamp(static_cast<double>(t), 0.0, length - 1) / (length - 1);
      value = end_ + (start_ - end_) * 0.5 * (1 + std::cos(std::numbers::pi * f));
    }
    // One reflection back into the band, then the global clip.
    if (value < band_lo_) {
      value = 2 * band_lo_ - value;
    } else if (value > band_hi_) {
      value = 2 * band_hi_ - value;
    }
    return Clip(value);
  }

 private:
  void Retarget() {
    Params::Retarget retarget = params_.retarget;
    if (retarget == Params::Retarget::kRandom) {
      retarget = random_.Bernoulli(0.5) ? Params::Retarget::kSwap : Params::Retarget::kRestart;
    }
    // swap: continue from where the last cycle ended; restart: from the episode's start.
    StartCycle(retarget == Params::Retarget::kSwap ? end_ : episode_centre_,
               /*retargeted=*/true);
  }

  void StartCycle(double centre, bool retargeted) {
    band_lo_ = min_;
    band_hi_ = max_;
    if (params_.neighborhood_radius.has_value()) {
      band_lo_ = std::max(min_, centre - *params_.neighborhood_radius);
      band_hi_ = std::min(max_, centre + *params_.neighborhood_radius);
    }
    start_ = std::clamp(centre, band_lo_, band_hi_);
    if (params_.mode == Params::Mode::kOnce && params_.end.has_value() && !retargeted) {
      end_ = std::clamp(*params_.end, band_lo_, band_hi_);
    } else {
      end_ = ChooseEnd();
    }
    if (params_.min_delta > 0 && std::abs(end_ - start_) < params_.min_delta) {
      end_ = Clip(start_ + (end_ >= start_ ? params_.min_delta : -params_.min_delta));
    }
  }

  // A band edge: the far one when the start sits near the other, else by `direction`.
  double ChooseEnd() {
    const double repel = params_.repel_edge_eps_frac * (band_hi_ - band_lo_);
    if (start_ - band_lo_ <= repel) return band_hi_;
    if (band_hi_ - start_ <= repel) return band_lo_;
    switch (params_.direction) {
      case Params::EndDirection::kToMin: return band_lo_;
      case Params::EndDirection::kToMax: return band_hi_;
      case Params::EndDirection::kRandom: return random_.Bernoulli(0.5) ? band_hi_ : band_lo_;
      case Params::EndDirection::kAuto:
        // The farther edge (the reference's comment says "nearest"; its code picks this).
        return start_ - band_lo_ < band_hi_ - start_ ? band_hi_ : band_lo_;
    }
    return band_hi_;
  }

  const Params params_;
  double episode_centre_ = 0;
  int64_t cycle_start_ = 0;
  int64_t cycle_length_ = 1;
  double band_lo_ = 0;
  double band_hi_ = 0;
  double start_ = 0;
  double end_ = 0;
};

}  // namespace

std::unique_ptr<Schedule> MakeSinusoidal(const ScheduleSpec& spec,
                                         const SinusoidalParams& params) {
  return std::make_unique<Sinusoidal>(spec, params);
}

std::unique_ptr<Schedule> MakeSinusoidalJump(const ScheduleSpec& spec,
                                             const SinusoidalJumpParams& params) {
  return std::make_unique<SinusoidalJump>(spec, params);
}

std::unique_ptr<Schedule> MakeCosineAnnealing(const ScheduleSpec& spec,
                                              const CosineAnnealingParams& params) {
  return std::make_unique<CosineAnnealing>(spec, params);
}

}  // namespace dcs::env::internal
