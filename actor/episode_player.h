// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_EPISODE_PLAYER_H_
#define DCS_ACTOR_EPISODE_PLAYER_H_

// One episode of a policy, rendered: what `dcs play` records. The policy acts
// deterministically (its mode, as in evaluation: actor/evaluation.h) in one DynamicContextEnv
// (its pools, schedules and observation mode as the options give them), which plays episode 0
// of its slot: the reset draws from StreamSeed(options.run_seed, "reset", {slot, 0}), so an
// episode is a function of the options and the policy alone.
//
// Frames: frame 0 shows the state after the reset, frame t the state after step t, so an
// episode of T steps (until terminated or truncated) has T + 1 frames. Each is the
// environment's scene (Env::Render, Env::kRenderWidth x kRenderHeight RGB), handed to the
// caller with what is true at that frame: the step, the return so far and every context
// feature's current value (a schedule may move one within the episode).
// Thread-compatible.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "actor/policy.h"
#include "actor/rollout_collector.h"
#include "common/status_macros.h"
#include "env/dynamic_context_env.h"
#include "env/raster.h"

namespace dcs::actor {

struct PlayedFrame {
  int64_t step = 0;               // transitions before this frame: 0 for the reset state
  double episode_return = 0;      // the rewards of those transitions, summed
  std::vector<double> features;   // every context feature's current value, by index
  const env::Canvas* scene = nullptr;  // the rendered state; valid during the callback only
};

struct PlayedEpisode {
  int64_t steps = 0;  // transitions: the episode has steps + 1 frames
  double episode_return = 0;
};

// Plays one episode of `policy` with `options`, calling `on_frame(const PlayedFrame&)` for
// each frame in order; `on_frame` returns absl::Status, and its first error stops the episode
// and is returned. INVALID_ARGUMENT as DynamicContextEnv::Create for bad options.
template <typename Env, typename OnFrame>
absl::StatusOr<PlayedEpisode> PlayEpisode(Policy& policy, env::DynamicContextOptions options,
                                          OnFrame&& on_frame);

// Implementation details.

template <typename Env, typename OnFrame>
absl::StatusOr<PlayedEpisode> PlayEpisode(Policy& policy, env::DynamicContextOptions options,
                                          OnFrame&& on_frame) {
  constexpr int kObs = Env::kObservationSize;
  constexpr int kAct = Env::kActionSize;
  const int num_features = Env::Features().size();
  DCS_ASSIGN_OR_RETURN(env::DynamicContextEnv<Env> environment,
                       env::DynamicContextEnv<Env>::Create(std::move(options)));
  std::vector<typename Env::Observation> observation(kObs);
  std::vector<float> context(environment.context_size());
  const std::span<typename Env::Observation, kObs> observation_span(observation.data(), kObs);
  environment.Reset(/*global_step=*/0, observation_span, context);

  env::Canvas scene(Env::kRenderWidth, Env::kRenderHeight);
  PlayedFrame frame{.features = std::vector<double>(num_features), .scene = &scene};
  const auto show = [&]() -> absl::Status {
    for (int i = 0; i < num_features; ++i) frame.features[i] = environment.feature(i);
    environment.env().Render(scene);
    return on_frame(static_cast<const PlayedFrame&>(frame));
  };
  DCS_RETURN_IF_ERROR(show());
  std::vector<float> inputs;
  std::vector<uint8_t> images;
  std::vector<float> action(kAct);
  std::array<typename Env::ActionElement, kAct> env_action;
  for (bool done = false; !done;) {
    inputs.clear();
    images.clear();
    AppendPolicyInput<Env>(observation, context, inputs, images);
    policy.Act(1, inputs, images, /*deterministic=*/true, /*randoms=*/{}, action);
    ToEnvAction<Env>(action, env_action);
    const env::StepResult step = environment.Step(env_action, observation_span, context);
    frame.step += 1;
    frame.episode_return += step.reward;
    done = step.done();
    DCS_RETURN_IF_ERROR(show());
  }
  return PlayedEpisode{.steps = frame.step, .episode_return = frame.episode_return};
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_EPISODE_PLAYER_H_
