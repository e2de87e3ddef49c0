// Copyright 2026 The DCS Authors.
//
// CarRacing-v3 throughput on one core, in environment steps per second INCLUDING the 96x96
// observation rendered at every step (the number that matters; target >= 5,000 steps/s):
//   BM_CarRacingStep/K          Step with a fixed action [0, 0.1, 0] (the car drives off and
//                               leaves the playfield after ~400 steps; the reset that follows
//                               is included), observation supersampled K x K (default K = 2)
//   BM_CarRacingCenterline/K    the centre-line driver racing laps (driver included): the
//                               realistic mix of road, kerbs and speed
//   BM_CarRacingScheduledComY   the dynamic-context wrapper moving COM_Y every step (so the
//                               payload body is re-created every step), centre-line driver
//   BM_CarRacingDraw/K          drawing one frame into the (96 K)^2 canvas only (no physics,
//                               no box filter)
//   BM_CarRacingReset           Reset: track generation, 300-odd tile fixtures, the car and the
//                               first step with its (zoomed-out) picture
//   BM_CarRacingTrack           the track generator alone

#include <array>
#include <string>

#include "benchmark/benchmark.h"
#include "env/car_racing.h"
#include "env/car_racing_centerline.h"
#include "env/dynamic_context_env.h"
#include "env/schedule_config.h"

namespace dcs::env {
namespace {

using Observation = std::array<uint8_t, CarRacing::kObservationSize>;  // 27 kB

// One step of the centre-line driver; a finished episode restarts on the next track.
void DriveCenterline(CarRacing& env, CenterlineDriver& driver, Random& random,
                     Observation& observation) {
  std::array<float, 3> action;
  driver.Act(env, action);
  if (env.Step(action, observation).done()) {
    env.Reset(random, observation);
    driver.Reset(env);
  }
}

void BM_CarRacingStep(benchmark::State& state) {
  CarRacing env(CarRacingOptions{.supersample = static_cast<int>(state.range(0))});
  Observation observation;
  Random random(0);
  env.Reset(random, observation);
  const std::array<float, 3> action = {0.0f, 0.1f, 0.0f};
  for (auto _ : state) {
    if (env.Step(action, observation).done()) env.Reset(random, observation);
    benchmark::DoNotOptimize(observation.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingStep)->Arg(1)->Arg(2)->Arg(3)->Arg(4);

void BM_CarRacingCenterline(benchmark::State& state) {
  CarRacing env(CarRacingOptions{.supersample = static_cast<int>(state.range(0))});
  Observation observation;
  Random random(0);
  env.Reset(random, observation);
  CenterlineDriver driver;
  driver.Reset(env);
  for (auto _ : state) {
    DriveCenterline(env, driver, random, observation);
    benchmark::DoNotOptimize(observation.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingCenterline)->Arg(2)->Arg(3)->Arg(4);

void BM_CarRacingScheduledComY(benchmark::State& state) {
  ScheduleConfig config{.family = "sinusoidal"};
  config.params = {{"amplitude_frac", 0.5}, {"period", 125.0}};
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, -0.8, 0.8, 7);
  if (!spec.ok()) {
    state.SkipWithError(std::string(spec.status().message()).c_str());
    return;
  }
  DynamicContextOptions options{
      .observe = ObserveMode::kLive, .observed_features = {CarRacing::kComY}, .run_seed = 1};
  options.schedules.push_back({CarRacing::kComY, {{.steps = 1 << 30, .spec = *spec}}});
  absl::StatusOr<DynamicContextEnv<CarRacing>> env =
      DynamicContextEnv<CarRacing>::Create(std::move(options));
  if (!env.ok()) {
    state.SkipWithError(std::string(env.status().message()).c_str());
    return;
  }
  Observation observation;
  std::array<float, 1> context;
  int64_t steps = 0;
  env->Reset(steps, observation, context);
  CenterlineDriver driver;
  driver.Reset(env->env());
  std::array<float, 3> action;
  for (auto _ : state) {
    driver.Act(env->env(), action);
    ++steps;
    if (env->Step(action, observation, context).done()) {
      env->Reset(steps, observation, context);
      driver.Reset(env->env());
    }
    benchmark::DoNotOptimize(observation.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingScheduledComY);

void BM_CarRacingDraw(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  CarRacing env;
  Observation observation;
  Random random(0);
  env.Reset(random, observation);
  CenterlineDriver driver;
  driver.Reset(env);
  for (int i = 0; i < 100; ++i) {  // past the zoom animation, on the road
    DriveCenterline(env, driver, random, observation);
  }
  Canvas canvas(96 * k, 96 * k);
  for (auto _ : state) {
    env.Render(canvas);
    benchmark::DoNotOptimize(canvas.pixels().data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingDraw)->Arg(1)->Arg(2)->Arg(3)->Arg(4);

void BM_CarRacingReset(benchmark::State& state) {
  CarRacing env;
  Observation observation;
  Random random(0);
  for (auto _ : state) {
    env.Reset(random, observation);
    benchmark::DoNotOptimize(observation.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingReset);

void BM_CarRacingTrack(benchmark::State& state) {
  Random random(0);
  for (auto _ : state) {
    Track track = GenerateTrack(random);
    benchmark::DoNotOptimize(track.points.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CarRacingTrack);

}  // namespace
}  // namespace dcs::env
