// Copyright 2026 The DCS Authors.
//
// CartPole stepping throughput, in environment steps per second on one core (the figure that
// matters; issue 3 targets >= 20 M bare steps/s, and a schedule plus live observation costing
// at most as much again):
//   BM_BareCartPole           CartPole::Step alone (reset in place when an episode ends)
//   BM_ScheduledCartPole/F    the dynamic-context wrapper with family F moving the pole length
//                             and the context observed live (F = none: wrapper, no schedule)
//   BM_VectorCartPole64       64 wrapped slots stepped as one batch with auto-reset
// Actions follow a fixed pattern so every variant does the same physics.

#include <array>
#include <string>
#include <vector>

#include "benchmark/benchmark.h"
#include "env/cartpole.h"
#include "env/dynamic_context_env.h"
#include "env/schedule_config.h"
#include "env/vector_env.h"

namespace dcs::env {
namespace {

constexpr double kLengthLo = 0.35;  // the paper's training range
constexpr double kLengthHi = 0.75;

int32_t ActionAt(int64_t step) { return static_cast<int32_t>((step * 7 + 3) % 5 < 2); }

void BM_BareCartPole(benchmark::State& state) {
  CartPole env;
  std::array<float, 4> observation;
  Random random(0);
  env.Reset(random, observation);
  int64_t step = 0;
  for (auto _ : state) {
    const std::array<int32_t, 1> action = {ActionAt(step++)};
    const StepResult result = env.Step(action, observation);
    if (result.done()) env.Reset(random, observation);
    benchmark::DoNotOptimize(observation);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BareCartPole);

// Families with the builder's defaults, plus the parameters a family requires.
ScheduleConfig BenchmarkConfig(const std::string& family) {
  ScheduleConfig config{.family = family};
  if (family == "sinusoidal") config.params = {{"amplitude_frac", 0.5}, {"period", 125.0}};
  if (family == "cosine_annealing") config.params = {{"T_0", 250.0}};
  if (family == "continuous_incrementer") config.params = {{"delta_frac", 0.005}};
  if (family == "piecewise_constant") {
    config.params = {{"values", std::vector<double>{0.35, 0.55, 0.75}}};
  }
  return config;
}

DynamicContextOptions WrappedOptions(const std::string& family, uint64_t slot) {
  DynamicContextOptions options{.observe = ObserveMode::kLive,
                                .observed_features = {CartPole::kLength},
                                .run_seed = 1,
                                .slot = slot};
  options.pools.push_back({CartPole::kLength, *ContextPool::OfSize(kLengthLo, kLengthHi, 7)});
  if (family != "none") {
    absl::StatusOr<ScheduleSpec> spec =
        ParseScheduleSpec(BenchmarkConfig(family), kLengthLo, kLengthHi, 7);
    options.schedules.push_back({CartPole::kLength, {{.steps = 1 << 30, .spec = *spec}}});
  }
  return options;
}

void BM_ScheduledCartPole(benchmark::State& state, const std::string& family) {
  absl::StatusOr<DynamicContextEnv<CartPole>> env =
      DynamicContextEnv<CartPole>::Create(WrappedOptions(family, 0));
  if (!env.ok()) {
    state.SkipWithError(std::string(env.status().message()).c_str());
    return;
  }
  std::array<float, 4> observation;
  std::array<float, 1> context;
  env->Reset(0, observation, context);
  int64_t step = 0;
  for (auto _ : state) {
    const std::array<int32_t, 1> action = {ActionAt(step++)};
    const StepResult result = env->Step(action, observation, context);
    if (result.done()) env->Reset(step, observation, context);
    benchmark::DoNotOptimize(observation);
    benchmark::DoNotOptimize(context);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_CAPTURE(BM_ScheduledCartPole, none, std::string("none"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, identity, std::string("identity"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, sinusoidal, std::string("sinusoidal"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, cosine_annealing, std::string("cosine_annealing"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, continuous_incrementer,
                  std::string("continuous_incrementer"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, piecewise_constant, std::string("piecewise_constant"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, random_walk, std::string("random_walk"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, sudden_jump, std::string("sudden_jump"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, ornstein_uhlenbeck, std::string("ornstein_uhlenbeck"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, sinusoidal_jump, std::string("sinusoidal_jump"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, phased_ou, std::string("phased_ou"));
BENCHMARK_CAPTURE(BM_ScheduledCartPole, levy_walk, std::string("levy_walk"));

void BM_VectorCartPole64(benchmark::State& state) {
  constexpr int kSlots = 64;
  std::vector<DynamicContextOptions> slots;
  for (int i = 0; i < kSlots; ++i) slots.push_back(WrappedOptions("sinusoidal", i));
  absl::StatusOr<VectorEnv<CartPole>> env = VectorEnv<CartPole>::Create(std::move(slots));
  if (!env.ok()) {
    state.SkipWithError(std::string(env.status().message()).c_str());
    return;
  }
  env->Reset();
  std::vector<int32_t> actions(kSlots);
  int64_t step = 0;
  for (auto _ : state) {
    for (int i = 0; i < kSlots; ++i) actions[i] = ActionAt(step + i);
    ++step;
    env->Step(actions);
    benchmark::DoNotOptimize(env->observations().data());
  }
  state.SetItemsProcessed(state.iterations() * kSlots);
}
BENCHMARK(BM_VectorCartPole64);

}  // namespace
}  // namespace dcs::env
