// Copyright 2026 The DCS Authors.
//
// The families that drift step by step: Continuous Incrementer, Random Walk, Ornstein-Uhlenbeck
// and Phased OU (docs/reference.md, "Schedule families"). All four skip their first call.

#include "env/schedule_internal.h"

namespace dcs::env::internal {
namespace {

class ContinuousIncrementer final : public BoundedSchedule {
 public:
  ContinuousIncrementer(const ScheduleSpec& spec, const ContinuousIncrementerParams& params)
      : BoundedSchedule(spec), params_(params) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    skip_.Arm();
    using EpisodeDirection = ContinuousIncrementerParams::EpisodeDirection;
    switch (params_.episode_direction) {
      case EpisodeDirection::kUp: sign_ = 1; break;
      case EpisodeDirection::kDown: sign_ = -1; break;
      case EpisodeDirection::kRandom: sign_ = random_.Uniform01() >= 0.5 ? 1 : -1; break;
      case EpisodeDirection::kNone: sign_ = DirectionSign(params_.direction, params_.direction_prob);
    }
    return Clip(initial);
  }

  double Next(int64_t /*k*/, double current) override {
    if (skip_.Consume()) return current;
    double sign = sign_;
    // Without a per-episode direction or reflection, "both" is a +-delta random walk.
    if (params_.edge_mode != EdgeMode::kReflect &&
        params_.episode_direction == ContinuousIncrementerParams::EpisodeDirection::kNone &&
        params_.direction == Direction::kBoth) {
      sign = DrawSign(params_.direction_prob);
    }
    if (params_.follow_predefined_prob.has_value() &&
        !random_.Bernoulli(*params_.follow_predefined_prob)) {
      sign = -sign;
    }
    double change = sign * params_.delta;
    if (params_.noise_std > 0) change += random_.Normal(0, params_.noise_std);
    double value = current + change;
    if (params_.edge_mode == EdgeMode::kReflect && (value < min_ || value > max_)) {
      value = Reflect(value);
      sign_ = -sign_;
    }
    return Clip(value);
  }

 private:
  const ContinuousIncrementerParams params_;
  SkipFirstCall skip_;
  double sign_ = 1;
};

class RandomWalk final : public BoundedSchedule {
 public:
  RandomWalk(const ScheduleSpec& spec, const RandomWalkParams& params)
      : BoundedSchedule(spec), std_(params.std) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    skip_.Arm();
    return Clip(initial);
  }

  double Next(int64_t /*k*/, double current) override {
    if (skip_.Consume()) return current;
    return Clip(current + random_.Normal(0, std_));
  }

 private:
  const double std_;
  SkipFirstCall skip_;
};

// Ornstein-Uhlenbeck toward a target `mu_`, which Phased OU redraws from time to time.
class OrnsteinUhlenbeck : public BoundedSchedule {
 public:
  OrnsteinUhlenbeck(const ScheduleSpec& spec, double theta, double sigma)
      : BoundedSchedule(spec), theta_(theta), sigma_(sigma) {}

 protected:
  double Revert(double current) {
    return Clip(current + theta_ * (mu_ - current) + random_.Normal(0, sigma_));
  }

  const double theta_;
  const double sigma_;
  double mu_ = 0;
  SkipFirstCall skip_;
};

class FixedTargetOu final : public OrnsteinUhlenbeck {
 public:
  FixedTargetOu(const ScheduleSpec& spec, const OrnsteinUhlenbeckParams& params)
      : OrnsteinUhlenbeck(spec, params.theta, params.sigma), params_(params) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    skip_.Arm();
    mu_ = params_.mu_is_episode_initial ? initial : params_.mu;
    return Clip(initial);
  }

  double Next(int64_t /*k*/, double current) override {
    if (skip_.Consume()) return current;
    return Revert(current);
  }

 private:
  const OrnsteinUhlenbeckParams params_;
};

class PhasedOu final : public OrnsteinUhlenbeck {
 public:
  PhasedOu(const ScheduleSpec& spec, const PhasedOuParams& params)
      : OrnsteinUhlenbeck(spec, params.theta, params.sigma), params_(params) {}

  double Reset(double initial, EpisodeId id) override {
    StartEpisode(id);
    skip_.Arm();
    DrawTarget();
    next_switch_ = DrawInterval(params_.interval);
    return Clip(initial);
  }

  double Next(int64_t k, double current) override {
    if (skip_.Consume()) return current;
    if (k >= next_switch_) {
      DrawTarget();
      next_switch_ += DrawInterval(params_.interval);
    }
    return Revert(current);
  }

 private:
  void DrawTarget() {
    mu_ = params_.values[random_.Integers(0, static_cast<int64_t>(params_.values.size()))];
  }

  const PhasedOuParams params_;
  int64_t next_switch_ = 0;
};

}  // namespace

std::unique_ptr<Schedule> MakeContinuousIncrementer(const ScheduleSpec& spec,
                                                    const ContinuousIncrementerParams& params) {
  return std::make_unique<ContinuousIncrementer>(spec, params);
}

std::unique_ptr<Schedule> MakeRandomWalk(const ScheduleSpec& spec, const RandomWalkParams& params) {
  return std::make_unique<RandomWalk>(spec, params);
}

std::unique_ptr<Schedule> MakeOrnsteinUhlenbeck(const ScheduleSpec& spec,
                                                const OrnsteinUhlenbeckParams& params) {
  return std::make_unique<FixedTargetOu>(spec, params);
}

std::unique_ptr<Schedule> MakePhasedOu(const ScheduleSpec& spec, const PhasedOuParams& params) {
  return std::make_unique<PhasedOu>(spec, params);
}

}  // namespace dcs::env::internal
