// Copyright 2026 The DCS Authors.
//
// One PPO update with SB3's defaults on CartPole's shape (2048 transitions of one slot, 10 epochs
// of 32 minibatches of 64: 320 gradient steps), the figure issue 5 asks to time separately,
// with its arithmetic rate: 1.12 GFLOP an update (each sample's forward pass through the
// 5 -> 64 -> 64 -> 2 policy and 5 -> 64 -> 64 -> 1 value MLPs is 9,024 multiply-adds, its
// backward pass 17,408; 2048 x 10 of both, and the rollout's forward pass), against the rate of
// a large Eigen matrix product on the same core (what the update's products could reach at best);
// and actor inference per step (Eigen, the 5 -> 64 -> 64 -> 2 MLP), target <= 1 us; and for
// CarRacing's image policy (NatureCNN on a 96 x 96 RGB frame, then the MLP), the network actors
// and `dcs train` act with, the learner's forward pass of one frame, and an update's epoch.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "actor/eigen_blocking.h"
#include "actor/policy_network.h"
#include "benchmark/benchmark.h"
#include "common/random.h"
#include "env/car_racing.h"
#include "learner/actor_critic.h"
#include "learner/ppo_learner.h"
#include "learner/torch_runtime.h"
#include "run/run_plan.h"

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
  // Multiply-adds: 2048 samples x 10 epochs x (9,024 forward + 17,408 backward) + 2048 x 9,024.
  constexpr double kFlopsPerUpdate = 2.0 * (2048.0 * 10 * (9024 + 17408) + 2048.0 * 9024);
  state.counters["GFLOP_per_s"] =
      benchmark::Counter(kFlopsPerUpdate * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PpoUpdateCartPole)->Unit(benchmark::kMillisecond);

// The ceiling: a 512 x 512 by 512 x 512 float product with Eigen (AVX2 and FMA, blocking pinned),
// one core.
void BM_EigenProduct512(benchmark::State& state) {
  actor::PinEigenBlocking();
  const Eigen::MatrixXf a = Eigen::MatrixXf::Random(512, 512);
  const Eigen::MatrixXf b = Eigen::MatrixXf::Random(512, 512);
  Eigen::MatrixXf c(512, 512);
  for (auto _ : state) {
    c.noalias() = a * b;
    benchmark::DoNotOptimize(c.data());
  }
  state.counters["GFLOP_per_s"] = benchmark::Counter(
      2.0 * 512 * 512 * 512 * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EigenProduct512)->Unit(benchmark::kMillisecond);

void BM_ActorInferenceCartPole(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(CartPoleSpec(), run::PpoConfig{}, 1, 0);
  actor::PolicyNetwork policy = *actor::PolicyNetwork::Create(learner->ActorWeights());
  Random random(3);
  std::vector<float> input = {0.01f, -0.2f, 0.03f, 0.1f, -0.5f};
  float action = 0;
  for (auto _ : state) {
    policy.Act(1, input, /*images=*/{}, /*deterministic=*/false, {&random, 1}, {&action, 1});
    benchmark::DoNotOptimize(action);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ActorInferenceCartPole);

// A 96 x 96 RGB frame and one context value, three continuous actions.
run::PolicySpec CarRacingSpec() { return run::PolicySpecFor<env::CarRacing>(1); }

std::vector<uint8_t> RandomFrame() {
  Random random(5);
  std::vector<uint8_t> frame(96 * 96 * 3);
  for (uint8_t& byte : frame) byte = static_cast<uint8_t>(random.Integers(0, 256));
  return frame;
}

void BM_ActorInferenceCarRacing(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  std::unique_ptr<PpoLearner> learner =
      *PpoLearner::Create(CarRacingSpec(), run::PpoConfig{}, 1, 0);
  actor::PolicyNetwork policy = *actor::PolicyNetwork::Create(learner->ActorWeights());
  Random random(3);
  const std::vector<uint8_t> frame = RandomFrame();
  std::vector<float> context = {0.25f};
  std::vector<float> action(3);
  for (auto _ : state) {
    policy.Act(1, context, frame, /*deterministic=*/false, {&random, 1}, action);
    benchmark::DoNotOptimize(action.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ActorInferenceCarRacing)->Unit(benchmark::kMicrosecond);

// The learner's forward pass of the same network on one frame.
void BM_LearnerForwardCarRacing(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  ActorCritic network(CarRacingSpec(), run::PpoConfig{});
  const std::vector<uint8_t> frame = RandomFrame();
  std::vector<float> context = {0.25f};
  const ObservationBatch batch{.flat = torch::from_blob(context.data(), {1, 1}), .images = frame};
  ActorCriticImpl::Pass pass;
  for (auto _ : state) {
    network->Forward(batch, /*for_backward=*/false, pass);
    benchmark::DoNotOptimize(pass.head.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_LearnerForwardCarRacing)->Unit(benchmark::kMicrosecond);

// One epoch of a PPO update on CarRacing's shape without context (2048 random RGB 96x96 frames:
// the rollout's forward pass, then 32 minibatches of 64, forward and backward): what an image
// policy's learning costs (an update is 10 epochs). NatureCNN's multiply-adds per frame:
// 9,934,848 forward (the convolutions' 3,250,176 + 3,276,800 + 2,359,296, the Linear's
// 1,048,576), 16,619,520 backward (every weight's gradient, and every input's but the image's).
void BM_PpoUpdateEpochCarRacing(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  constexpr int kSteps = 2048;
  run::PolicySpec spec = CarRacingSpec();
  spec.context_size = 0;
  run::PpoConfig config;
  config.n_epochs = 1;
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(spec, config, 1, 0);
  Random random(1);
  actor::Rollout rollout{.num_steps = kSteps, .num_envs = 1};
  rollout.images.resize(spec.image_size() * kSteps);
  for (uint8_t& pixel : rollout.images) pixel = static_cast<uint8_t>(random.Integers(0, 256));
  for (int t = 0; t < kSteps; ++t) {
    rollout.actions.push_back(static_cast<float>(random.Uniform(-1, 1)));
    rollout.actions.push_back(static_cast<float>(random.Uniform(0, 1)));
    rollout.actions.push_back(static_cast<float>(random.Uniform(0, 1)));
    rollout.rewards.push_back(static_cast<float>(random.Uniform(-0.1, 1)));
    rollout.episode_starts.push_back(t % 1000 == 0);
  }
  rollout.last_images.assign(spec.image_size(), 0);
  rollout.last_dones = {0};
  for (auto _ : state) {
    absl::StatusOr<UpdateStats> stats = learner->Update(rollout);
    if (!stats.ok()) state.SkipWithError(stats.status().ToString().c_str());
    benchmark::DoNotOptimize(stats);
  }
  constexpr double kFlopsPerEpoch = 2.0 * kSteps * (2 * 9934848.0 + 16619520.0);
  state.counters["GFLOP_per_s"] =
      benchmark::Counter(kFlopsPerEpoch * state.iterations() / 1e9, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PpoUpdateEpochCarRacing)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace
}  // namespace dcs::learner
