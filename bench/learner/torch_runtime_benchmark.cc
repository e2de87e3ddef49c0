// Copyright 2026 The DCS Authors.
//
// What the pinned numeric kernels (learner/torch_runtime.h) cost an image policy: one epoch of
// a PPO update on CarRacing's shape (2048 RGB 96x96 frames through NatureCNN: values and
// log-probabilities of the rollout, then 32 minibatches of 64), with convolutions in oneDNN
// (/onednn:1, libtorch's default) or in ATen and OpenBLAS (/onednn:0, as PinNumericKernels
// sets). The number that matters: seconds per epoch (an update is 10 epochs). Run it with the
// OPENBLAS_CORETYPE and ATEN_CPU_CAPABILITY to compare (bench/RESULTS.md); CartPole's update
// is timed in ppo_learner_benchmark.cc.

#include <ATen/Context.h>

#include <memory>
#include <vector>

#include "benchmark/benchmark.h"
#include "common/random.h"
#include "learner/ppo_learner.h"
#include "learner/torch_runtime.h"

namespace dcs::learner {
namespace {

constexpr int kHeight = 96;
constexpr int kWidth = 96;
constexpr int kChannels = 3;
constexpr int kActions = 3;
constexpr int kSteps = 2048;

run::PolicySpec CarRacingSpec() {
  return {.image_height = kHeight,
          .image_width = kWidth,
          .image_channels = kChannels,
          .action_size = kActions,
          .action_low = {-1, 0, 0},
          .action_high = {1, 1, 1}};
}

actor::Rollout RandomImageRollout(uint64_t seed) {
  Random random(seed);
  actor::Rollout rollout{.num_steps = kSteps, .num_envs = 1};
  rollout.images.resize(static_cast<size_t>(kSteps) * kHeight * kWidth * kChannels);
  for (uint8_t& pixel : rollout.images) pixel = static_cast<uint8_t>(random.Integers(0, 256));
  for (int t = 0; t < kSteps; ++t) {
    for (int i = 0; i < kActions; ++i) {
      rollout.actions.push_back(static_cast<float>(random.Uniform(-1, 1)));
    }
    rollout.rewards.push_back(static_cast<float>(random.Uniform(-0.1, 1)));
    rollout.episode_starts.push_back(t % 1000 == 0);
  }
  rollout.last_images.assign(static_cast<size_t>(kHeight) * kWidth * kChannels, 0);
  rollout.last_dones = {0};
  return rollout;
}

void BM_PpoUpdateEpochNatureCnn(benchmark::State& state) {
  PinTorchThreads(1).IgnoreError();
  at::globalContext().setUserEnabledMkldnn(state.range(0) == 1);
  run::PpoConfig config;
  config.n_epochs = 1;
  std::unique_ptr<PpoLearner> learner = *PpoLearner::Create(CarRacingSpec(), config, 1, 0);
  const actor::Rollout rollout = RandomImageRollout(1);
  for (auto _ : state) {
    absl::StatusOr<UpdateStats> stats = learner->Update(rollout);
    if (!stats.ok()) state.SkipWithError(stats.status().ToString().c_str());
    benchmark::DoNotOptimize(stats);
  }
  state.SetLabel(NumericFingerprint());
}
BENCHMARK(BM_PpoUpdateEpochNatureCnn)
    ->ArgName("onednn")
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kSecond)
    ->Iterations(2);

}  // namespace
}  // namespace dcs::learner
