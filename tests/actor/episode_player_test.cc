// Copyright 2026 The DCS Authors.
//
// One episode played and rendered (actor/episode_player.h): a frame for the reset and one per
// step, each with the step, the return so far and the context as it stands then; a schedule
// moves its feature from frame to frame, and an error of the frame's callback stops the episode.

#include "actor/episode_player.h"

#include <limits>
#include <set>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/policy_network.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "env/schedule_config.h"
#include "gtest/gtest.h"

namespace dcs::actor {
namespace {

// CartPole's policy that always pushes right: zero weights, and a bias favouring action 1.
PolicyNetwork PushRight() {
  PolicyWeights weights{.num_actions = 2};
  weights.layers.push_back({.inputs = 4,
                            .outputs = 2,
                            .weight = std::vector<float>(8, 0.0f),
                            .bias = {0.0f, 1.0f},
                            .activation = Activation::kNone});
  return *PolicyNetwork::Create(weights);
}

struct Frame {
  int64_t step;
  double episode_return;
  double length;
  int width;
};

absl::StatusOr<std::vector<Frame>> Play(env::DynamicContextOptions options) {
  PolicyNetwork policy = PushRight();
  const int length = *env::CartPole::Features().IndexOf("length");
  std::vector<Frame> frames;
  absl::StatusOr<PlayedEpisode> episode =
      PlayEpisode<env::CartPole>(policy, std::move(options), [&](const PlayedFrame& frame) {
        frames.push_back({frame.step, frame.episode_return, frame.features[length],
                          frame.scene->width()});
        return absl::OkStatus();
      });
  if (!episode.ok()) return episode.status();
  EXPECT_EQ(static_cast<int64_t>(frames.size()), episode->steps + 1);
  EXPECT_EQ(frames.back().episode_return, episode->episode_return);
  return frames;
}

TEST(EpisodePlayerTest, AFrameForTheResetAndOnePerStep) {
  absl::StatusOr<std::vector<Frame>> frames = Play({.run_seed = 3});
  ASSERT_TRUE(frames.ok()) << frames.status();
  ASSERT_GT(frames->size(), 2u);  // pushing right topples the pole in a few steps
  ASSERT_LT(frames->size(), 100u);
  for (size_t i = 0; i < frames->size(); ++i) {
    EXPECT_EQ((*frames)[i].step, static_cast<int64_t>(i));
    EXPECT_EQ((*frames)[i].episode_return, static_cast<double>(i));  // CartPole: 1 a step
    EXPECT_EQ((*frames)[i].length, 0.5);  // no schedule: the default, held
    EXPECT_EQ((*frames)[i].width, env::CartPole::kRenderWidth);
  }
}

TEST(EpisodePlayerTest, AScheduleMovesItsFeatureFromFrameToFrame) {
  const int length = *env::CartPole::Features().IndexOf("length");
  absl::StatusOr<env::ScheduleSpec> wave = env::ParseScheduleSpec(
      {.family = "sinusoidal", .params = {{"amplitude_frac", 0.5}, {"period", 4.0}}}, 0.3, 0.7,
      1);
  ASSERT_TRUE(wave.ok()) << wave.status();
  absl::StatusOr<std::vector<Frame>> frames = Play(
      {.schedules = {{.feature = length,
                      .stages = {{.steps = std::numeric_limits<int64_t>::max(),
                                  .spec = *wave}}}},
       .run_seed = 3});
  ASSERT_TRUE(frames.ok()) << frames.status();
  std::set<double> lengths;
  for (const Frame& frame : *frames) lengths.insert(frame.length);
  EXPECT_GT(lengths.size(), 2u);
}

TEST(EpisodePlayerTest, TheCallbacksErrorStopsTheEpisode) {
  PolicyNetwork policy = PushRight();
  int frames = 0;
  absl::StatusOr<PlayedEpisode> episode =
      PlayEpisode<env::CartPole>(policy, {}, [&](const PlayedFrame&) {
        return ++frames == 2 ? absl::InternalError("encoder stopped") : absl::OkStatus();
      });
  EXPECT_EQ(episode.status(), absl::InternalError("encoder stopped"));
  EXPECT_EQ(frames, 2);
}

}  // namespace
}  // namespace dcs::actor
