// Copyright 2026 The DCS Authors.
//
// One PPO update with SB3's defaults on CartPole's shape (2048 transitions of one slot, 10 epochs
// of 32 minibatches of 64: 320 gradient steps), the figure issue 5 asks to time separately;
// and actor inference per step (Eigen, the 5 -> 64 -> 64 -> 2 MLP), target <= 1 us.

#include <vector>

#include "actor/mlp_policy.h"
#include "benchmark/benchmark.h"
#include "common/random.h"
#include "learner/ppo_learner.h"
#include "learner/torch_runtime.h"

namespace dcs::learner {
namespace {

run::PolicySpec CartPoleSpec() {
  return {.observation_size = 4, .context_size = 1, .num_actions = 2, .action_size = 1};
}

actor::Rollout RandomRollout(int steps, uint64_t seed) {
  Random random(seed);
  actor::Rollout rollout{.num_steps = steps, .num_envs = 1};
  for (int t = 0; t < steps; ++t) {
    for (int i = 0; i < 5; ++i) rollout.inputs.push_back(static_cast<float>(random.Uniform(-1, 1)));
    rollout.actions.push_back(static_cast<float>(random.Integers(0, 2)));
    rollout.rewards.push_back(1.0f);
    rollout.episode_starts.push_back(t % 100 == 0);
  }
  rollout.last_inputs = std::vector<float>(5, 0.0f);
  rollout.last_dones = {0};
  return rollout;
}

void BM_PpoUpdateCartPole(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(CartPoleSpec(), run::PpoConfig{}, 1, 0);
  const actor::Rollout rollout = RandomRollout(2048, 1);
  for (auto _ : state) {
    absl::StatusOr<UpdateStats> stats = learner->Update(rollout);
    benchmark::DoNotOptimize(stats);
  }
  state.counters["gradient_steps_per_s"] =
      benchmark::Counter(320.0 * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PpoUpdateCartPole)->Unit(benchmark::kMillisecond);

void BM_ActorInferenceCartPole(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(CartPoleSpec(), run::PpoConfig{}, 1, 0);
  actor::MlpPolicy policy = *actor::MlpPolicy::Create(learner->ActorWeights());
  Random random(3);
  std::vector<float> input = {0.01f, -0.2f, 0.03f, 0.1f, -0.5f};
  float action = 0;
  for (auto _ : state) {
    policy.Act(input, /*deterministic=*/false, random, {&action, 1});
    benchmark::DoNotOptimize(action);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ActorInferenceCartPole);

}  // namespace
}  // namespace dcs::learner
