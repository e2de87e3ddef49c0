// Copyright 2026 The DCS Authors.
//
// BipedalWalker stepping throughput, in environment steps per second on one core (the figure
// that matters; the target is >= 50,000 bare steps/s). Box2D's 180 velocity and 60 position
// iterations per step dominate; resets (a new terrain of 200 bodies) are included whenever an
// episode ends:
//   BM_BareWalker/random      BipedalWalker::Step without payload (Gymnasium's walker), uniform
//                             random actions (short episodes: it falls, so resets weigh more)
//   BM_BareWalker/heuristic   the same with the heuristic gait (long episodes, mostly walking)
//   BM_Reset                  BipedalWalker::Reset alone (terrain, clouds, walker, one step)
//   BM_WorldStepOnly          the Box2D floor: recorded heuristic episodes replayed through
//                             WalkerWorld::SetMotors and Step alone (no lidar, observation or
//                             reward; rebuilds untimed), checked to retrace the same trajectory
//   BM_ScheduledWalker/F      the dynamic-context wrapper, the paper's payload (2 kg, 0.5 m),
//                             heuristic actions (episodes of about 110 steps), COM_X moved by
//                             schedule family F and observed live (F = none: no schedule), so
//                             the payload fixture is re-created at every step the value changes
//   BM_VectorWalker16         16 wrapped slots with a sinusoidal COM_X, random actions

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "benchmark/benchmark.h"
#include "env/bipedal_walker.h"
#include "env/bipedal_walker_heuristic.h"
#include "env/dynamic_context_env.h"
#include "env/schedule_config.h"
#include "env/vector_env.h"

namespace dcs::env {
namespace {

constexpr double kComLo = -0.6;  // the paper's training range
constexpr double kComHi = 0.6;

// Gymnasium's walker: DCS's default context without the payload.
BipedalWalker GymnasiumWalker() {
  BipedalWalker env;
  env.SetFeature(BipedalWalker::kPayloadMass, 0);
  return env;
}

void RandomAction(Random& random, std::array<float, 4>& action) {
  for (float& a : action) a = static_cast<float>(random.Uniform(-1, 1));
}

void BM_BareWalker(benchmark::State& state, bool heuristic) {
  BipedalWalker env = GymnasiumWalker();
  std::array<float, 24> observation;
  std::array<float, 4> action = {0, 0, 0, 0};
  Random random(0);
  Random action_random(1);
  WalkerHeuristic gait;
  env.Reset(random, observation);
  for (auto _ : state) {
    const StepResult result = env.Step(action, observation);
    if (result.done()) {
      env.Reset(random, observation);
      gait.Reset();
      action = {0, 0, 0, 0};
    } else if (heuristic) {
      action = gait.Act(observation);
    } else {
      RandomAction(action_random, action);
    }
    benchmark::DoNotOptimize(observation);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_BareWalker, random, false);
BENCHMARK_CAPTURE(BM_BareWalker, heuristic, true);

void BM_Reset(benchmark::State& state) {
  BipedalWalker env = GymnasiumWalker();
  std::array<float, 24> observation;
  Random random(0);
  for (auto _ : state) {
    env.Reset(random, observation);
    benchmark::DoNotOptimize(observation);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Reset);

// One heuristic episode of Gymnasium's walker, as its seed and actions.
struct RecordedEpisode {
  uint64_t seed;
  std::vector<std::array<float, 4>> actions;
  b2Vec2 final_hull_position;
};

RecordedEpisode RecordHeuristicEpisode(uint64_t seed) {
  BipedalWalker env = GymnasiumWalker();
  std::array<float, 24> observation;
  Random random(seed);
  env.Reset(random, observation);
  WalkerHeuristic gait;
  RecordedEpisode episode{.seed = seed};
  for (bool done = false; !done;) {
    episode.actions.push_back(gait.Act(observation));
    done = env.Step(episode.actions.back(), observation).done();
  }
  episode.final_hull_position = env.world().hull()->GetPosition();
  return episode;
}

double DefaultFeature(BipedalWalker::Feature feature) {
  return BipedalWalker::Features().feature(feature).default_value;
}

// Sets the motors for `action` and steps the world, as BipedalWalker's step does with default
// features (Gymnasium's constants).
void StepWorld(WalkerWorld& world, std::span<const float, 4> action) {
  world.SetMotors(action, DefaultFeature(BipedalWalker::kSpeedHip),
                  DefaultFeature(BipedalWalker::kSpeedKnee),
                  DefaultFeature(BipedalWalker::kMotorsTorque));
  world.Step(1.0 / DefaultFeature(BipedalWalker::kFps));
}

// Builds the episode's world as BipedalWalker::Reset does, including its internal zero-action
// step.
void BuildEpisodeWorld(const RecordedEpisode& episode, WalkerWorld& world) {
  Random random(episode.seed);
  world.Build(WalkerGeometry{}, DefaultFeature(BipedalWalker::kFriction),
              DefaultFeature(BipedalWalker::kMotorsTorque), random);
  StepWorld(world, std::array<float, 4>{0, 0, 0, 0});
}

void BM_WorldStepOnly(benchmark::State& state) {
  std::vector<RecordedEpisode> episodes;
  for (uint64_t seed = 0; seed < 4; ++seed) episodes.push_back(RecordHeuristicEpisode(seed));
  auto world = std::make_unique<WalkerWorld>();
  size_t episode = 0;
  size_t step = 0;
  BuildEpisodeWorld(episodes[episode], *world);
  for (auto _ : state) {
    StepWorld(*world, episodes[episode].actions[step]);
    if (++step < episodes[episode].actions.size()) continue;
    state.PauseTiming();
    const b2Vec2 replayed = world->hull()->GetPosition();
    const b2Vec2 recorded = episodes[episode].final_hull_position;
    if (replayed.x != recorded.x || replayed.y != recorded.y) {
      state.SkipWithError("the replay left the recorded trajectory");
      break;
    }
    episode = (episode + 1) % episodes.size();
    step = 0;
    BuildEpisodeWorld(episodes[episode], *world);
    state.ResumeTiming();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_WorldStepOnly);

ScheduleConfig BenchmarkConfig(const std::string& family) {
  ScheduleConfig config{.family = family};
  if (family == "sinusoidal") config.params = {{"amplitude_frac", 0.5}, {"period", 125.0}};
  if (family == "continuous_incrementer") config.params = {{"delta_frac", 0.005}};
  return config;
}

DynamicContextOptions WrappedOptions(const std::string& family, uint64_t slot) {
  DynamicContextOptions options{.observe = ObserveMode::kLive,
                                .observed_features = {BipedalWalker::kComX},
                                .run_seed = 1,
                                .slot = slot};
  options.pools.push_back({BipedalWalker::kComX, *ContextPool::OfSize(kComLo, kComHi, 3)});
  if (family != "none") {
    absl::StatusOr<ScheduleSpec> spec =
        ParseScheduleSpec(BenchmarkConfig(family), kComLo, kComHi, 7);
    options.schedules.push_back({BipedalWalker::kComX, {{.steps = 1 << 30, .spec = *spec}}});
  }
  return options;
}

void BM_ScheduledWalker(benchmark::State& state, const std::string& family) {
  absl::StatusOr<DynamicContextEnv<BipedalWalker>> env =
      DynamicContextEnv<BipedalWalker>::Create(WrappedOptions(family, 0));
  if (!env.ok()) {
    state.SkipWithError(std::string(env.status().message()).c_str());
    return;
  }
  std::array<float, 24> observation;
  std::array<float, 1> context;
  std::array<float, 4> action = {0, 0, 0, 0};
  WalkerHeuristic gait;
  env->Reset(0, observation, context);
  int64_t step = 0;
  for (auto _ : state) {
    const StepResult result = env->Step(action, observation, context);
    ++step;
    if (result.done()) {
      env->Reset(step, observation, context);
      gait.Reset();
      action = {0, 0, 0, 0};
    } else {
      action = gait.Act(observation);
    }
    benchmark::DoNotOptimize(observation);
    benchmark::DoNotOptimize(context);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_ScheduledWalker, none, std::string("none"));
BENCHMARK_CAPTURE(BM_ScheduledWalker, sinusoidal, std::string("sinusoidal"));
BENCHMARK_CAPTURE(BM_ScheduledWalker, continuous_incrementer,
                  std::string("continuous_incrementer"));

void BM_VectorWalker16(benchmark::State& state) {
  constexpr int kSlots = 16;
  std::vector<DynamicContextOptions> slots;
  for (int i = 0; i < kSlots; ++i) slots.push_back(WrappedOptions("sinusoidal", i));
  absl::StatusOr<VectorEnv<BipedalWalker>> env = VectorEnv<BipedalWalker>::Create(std::move(slots));
  if (!env.ok()) {
    state.SkipWithError(std::string(env.status().message()).c_str());
    return;
  }
  env->Reset();
  std::vector<float> actions(kSlots * 4);
  Random action_random(1);
  for (auto _ : state) {
    for (float& a : actions) a = static_cast<float>(action_random.Uniform(-1, 1));
    env->Step(actions);
    benchmark::DoNotOptimize(env->observations().data());
  }
  state.SetItemsProcessed(state.iterations() * kSlots);
}
BENCHMARK(BM_VectorWalker16);

}  // namespace
}  // namespace dcs::env
