// Copyright 2026 The DCS Authors.
//
// The factory, and the families built from others: Identity, Sequential composite and the
// Levy walk (docs/reference.md, "Schedule families").

#include "env/schedule.h"

#include <utility>
#include <vector>

#include "common/random.h"
#include "env/schedule_internal.h"

namespace dcs::env {
namespace internal {
namespace {

class Identity final : public BoundedSchedule {
 public:
  explicit Identity(const ScheduleSpec& spec) : BoundedSchedule(spec) {}
  double Reset(double initial, EpisodeId /*id*/) override { return Clip(initial); }
  double Next(int64_t /*k*/, double current) override { return current; }
};

class Sequential final : public Schedule {
 public:
  explicit Sequential(std::vector<std::unique_ptr<Schedule>> parts) : parts_(std::move(parts)) {}

  double Reset(double initial, EpisodeId id) override {
    double value = initial;
    for (auto& part : parts_) value = part->Reset(value, id);
    return value;
  }

  double Next(int64_t k, double current) override {
    double value = current;
    for (auto& part : parts_) value = part->Next(k, value);
    return value;
  }

 private:
  std::vector<std::unique_ptr<Schedule>> parts_;
};

std::unique_ptr<Schedule> MakeSequential(const SequentialParams& params) {
  std::vector<std::unique_ptr<Schedule>> parts;
  for (const ScheduleSpec& part : params.parts) parts.push_back(MakeSchedule(part));
  return std::make_unique<Sequential>(std::move(parts));
}

// A sudden jump (both directions, clipped) then a random-walk step, with spawned seeds.
std::unique_ptr<Schedule> MakeLevyWalk(const ScheduleSpec& spec, const LevyWalkParams& params) {
  ScheduleSpec jump = spec;
  jump.seed = SpawnSeed(spec.seed, 0);
  jump.params = SuddenJumpParams{.step_size = params.step_size,
                                 .interval = params.interval,
                                 .direction = Direction::kBoth,
                                 .direction_prob = 0.5,
                                 .edge_mode = EdgeMode::kClip};
  ScheduleSpec walk = spec;
  walk.seed = SpawnSeed(spec.seed, 1);
  walk.params = RandomWalkParams{.std = params.std};
  return MakeSequential(SequentialParams{.parts = {std::move(jump), std::move(walk)}});
}

}  // namespace

uint32_t SpawnSeed(uint32_t seed, uint32_t child) {
  // numpy pads the parent's entropy to its 4-word pool, then appends the spawn key.
  return SeedSequence({seed, 0, 0, 0, child}).GenerateState32(1)[0];
}

std::unique_ptr<Schedule> MakeIdentity(const ScheduleSpec& spec) {
  return std::make_unique<Identity>(spec);
}

}  // namespace internal

std::vector<double> ScheduleTrajectory(Schedule& schedule, double initial, EpisodeId id,
                                       int transitions) {
  std::vector<double> values;
  values.reserve(transitions);
  double value = schedule.Reset(initial, id);
  for (int k = 0; k < transitions; ++k) {
    if (k > 0) value = schedule.Next(k, value);
    values.push_back(value);
  }
  return values;
}

std::unique_ptr<Schedule> MakeSchedule(const ScheduleSpec& spec) {
  using namespace internal;  // NOLINT: the family factories
  return std::visit(
      [&spec](const auto& params) -> std::unique_ptr<Schedule> {
        using P = std::decay_t<decltype(params)>;
        if constexpr (std::is_same_v<P, IdentityParams>) return MakeIdentity(spec);
        if constexpr (std::is_same_v<P, ContinuousIncrementerParams>) {
          return MakeContinuousIncrementer(spec, params);
        }
        if constexpr (std::is_same_v<P, SuddenJumpParams>) return MakeSuddenJump(spec, params);
        if constexpr (std::is_same_v<P, RandomWalkParams>) return MakeRandomWalk(spec, params);
        if constexpr (std::is_same_v<P, OrnsteinUhlenbeckParams>) {
          return MakeOrnsteinUhlenbeck(spec, params);
        }
        if constexpr (std::is_same_v<P, PiecewiseConstantParams>) {
          return MakePiecewiseConstant(spec, params);
        }
        if constexpr (std::is_same_v<P, SinusoidalParams>) return MakeSinusoidal(spec, params);
        if constexpr (std::is_same_v<P, CosineAnnealingParams>) {
          return MakeCosineAnnealing(spec, params);
        }
        if constexpr (std::is_same_v<P, SinusoidalJumpParams>) {
          return MakeSinusoidalJump(spec, params);
        }
        if constexpr (std::is_same_v<P, PhasedOuParams>) return MakePhasedOu(spec, params);
        if constexpr (std::is_same_v<P, LevyWalkParams>) return MakeLevyWalk(spec, params);
        if constexpr (std::is_same_v<P, SequentialParams>) return MakeSequential(params);
      },
      spec.params);
}

}  // namespace dcs::env
