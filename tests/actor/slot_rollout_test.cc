// Copyright 2026 The DCS Authors.
//
// SlotRollout (actor/slot_rollout.h) on hand-made parts: the merge's [t][e] layout, its order
// of truncations and finished episodes, and the parts it refuses. That merged parts equal what
// one collector over every slot gives is tests/actor/rollout_collector_test.cc's.

#include "actor/slot_rollout.h"

#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "actor/rollout.h"
#include "actor/rollout_collector.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::actor {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr int kSteps = 2;

// Slot `slot`'s part with kSteps steps, inputs of 2 floats and actions of 1, each value telling
// its slot and step: input (t, k) is 100 slot + 10 t + k, action t is 100 slot + t.
SlotRollout Part(int slot) {
  SlotRollout part{.slot = slot, .num_steps = kSteps};
  const float base = 100.0f * static_cast<float>(slot);
  for (int t = 0; t < kSteps; ++t) {
    const float at = base + 10.0f * static_cast<float>(t);
    part.inputs.insert(part.inputs.end(), {at, at + 1});
    part.actions.push_back(base + static_cast<float>(t));
    part.rewards.push_back(base + static_cast<float>(t));
    part.episode_starts.push_back(t == 0 ? 1 : 0);
  }
  part.last_input = {base + 90, base + 91};
  part.last_done = slot == 1;
  part.journal = {.episode = slot, .reset_step = 10 * slot};
  return part;
}

Rollout::Truncation Cut(int step, float value) { return {.step = step, .input = {value, value}}; }

// The merge's error message; a test failure if it succeeds or fails with another code.
std::string MergeError(std::vector<SlotRollout> parts) {
  absl::StatusOr<MergedRollout> merged = MergeSlotRollouts(std::move(parts));
  EXPECT_EQ(merged.status().code(), absl::StatusCode::kInvalidArgument) << merged.status();
  return std::string(merged.status().message());
}

TEST(SlotRolloutTest, MakeSlotRolloutTakesAOneSlotRollout) {
  Rollout one{.num_steps = 1,
              .num_envs = 1,
              .inputs = {1, 2},
              .actions = {3},
              .rewards = {4},
              .episode_starts = {1},
              .truncations = {Cut(0, 5)},
              .last_inputs = {6, 7},
              .last_dones = {1}};
  const SlotRollout part =
      MakeSlotRollout(std::move(one), 2, {{.episode_return = 8, .length = 9, .step = 0}},
                      {.episode = 3, .reset_step = 12});
  EXPECT_EQ(part.slot, 2);
  EXPECT_EQ(part.num_steps, 1);
  EXPECT_THAT(part.inputs, ElementsAre(1, 2));
  EXPECT_THAT(part.actions, ElementsAre(3));
  EXPECT_THAT(part.rewards, ElementsAre(4));
  EXPECT_THAT(part.episode_starts, ElementsAre(1));
  ASSERT_EQ(part.truncations.size(), 1u);
  EXPECT_THAT(part.truncations[0].input, ElementsAre(5, 5));
  EXPECT_THAT(part.last_input, ElementsAre(6, 7));
  EXPECT_TRUE(part.last_done);
  ASSERT_EQ(part.finished.size(), 1u);
  EXPECT_EQ(part.finished[0].length, 9);
  EXPECT_EQ(part.journal.reset_step, 12);
}

TEST(SlotRolloutTest, PartsBecomeColumnsInSlotOrder) {
  absl::StatusOr<MergedRollout> merged = MergeSlotRollouts({Part(2), Part(0), Part(1)});
  ASSERT_TRUE(merged.ok()) << merged.status();
  const Rollout& rollout = merged->rollout;
  EXPECT_EQ(rollout.num_steps, kSteps);
  EXPECT_EQ(rollout.num_envs, 3);
  EXPECT_THAT(rollout.inputs, ElementsAre(0, 1, 100, 101, 200, 201, 10, 11, 110, 111, 210, 211));
  EXPECT_TRUE(rollout.images.empty());
  EXPECT_THAT(rollout.actions, ElementsAre(0, 100, 200, 1, 101, 201));
  EXPECT_THAT(rollout.rewards, ElementsAre(0, 100, 200, 1, 101, 201));
  EXPECT_THAT(rollout.episode_starts, ElementsAre(1, 1, 1, 0, 0, 0));
  EXPECT_THAT(rollout.last_inputs, ElementsAre(90, 91, 190, 191, 290, 291));
  EXPECT_THAT(rollout.last_dones, ElementsAre(0, 1, 0));
  ASSERT_EQ(merged->journals.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(merged->journals[i].reset_step, 10 * i) << i;
}

TEST(SlotRolloutTest, TruncationsAndFinishedEpisodesGoByStepThenSlot) {
  std::vector<SlotRollout> parts = {Part(0), Part(1)};
  parts[0].truncations = {Cut(1, 0.5f)};
  parts[1].truncations = {Cut(0, 1.0f), Cut(1, 1.5f)};
  parts[0].finished = {{.length = 11, .step = 1}};
  parts[1].finished = {{.length = 20, .step = 0}, {.length = 21, .step = 1}};
  absl::StatusOr<MergedRollout> merged = MergeSlotRollouts({parts[1], parts[0]});
  ASSERT_TRUE(merged.ok()) << merged.status();
  const std::vector<Rollout::Truncation>& cuts = merged->rollout.truncations;
  ASSERT_EQ(cuts.size(), 3u);
  EXPECT_EQ(cuts[0].step, 0);
  EXPECT_EQ(cuts[0].env, 1);
  EXPECT_THAT(cuts[0].input, ElementsAre(1.0f, 1.0f));
  EXPECT_EQ(cuts[1].step, 1);
  EXPECT_EQ(cuts[1].env, 0);
  EXPECT_THAT(cuts[1].input, ElementsAre(0.5f, 0.5f));
  EXPECT_EQ(cuts[2].step, 1);
  EXPECT_EQ(cuts[2].env, 1);
  EXPECT_THAT(cuts[2].input, ElementsAre(1.5f, 1.5f));
  std::vector<int64_t> lengths;
  for (const EpisodeSummary& episode : merged->finished) lengths.push_back(episode.length);
  EXPECT_THAT(lengths, ElementsAre(20, 11, 21));
}

TEST(SlotRolloutTest, RefusesPartsThatAreNotEachSlotOnce) {
  EXPECT_THAT(MergeError({}), HasSubstr("needs a slot"));
  EXPECT_THAT(MergeError({Part(0), Part(2)}), HasSubstr("slot 1 is missing"));
  EXPECT_THAT(MergeError({Part(1), Part(2)}), HasSubstr("slot 0 is missing"));
  EXPECT_THAT(MergeError({Part(1), Part(0), Part(1)}), HasSubstr("slot 1 is given twice"));
  EXPECT_THAT(MergeError({Part(-1), Part(0)}), HasSubstr("slot -1 is negative"));
}

TEST(SlotRolloutTest, RefusesPartsOfOtherShapes) {
  std::vector<SlotRollout> parts = {Part(0), Part(1)};
  parts[1].num_steps = 3;
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: num_steps is 3, expected 2"));

  parts = {Part(0), Part(1)};
  parts[0].num_steps = 0;
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 0: num_steps is 0"));

  parts = {Part(0), Part(1)};
  parts[0].inputs.pop_back();
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 0: inputs has 3 values, not a multiple of 2"));

  parts = {Part(0), Part(1)};
  parts[1].inputs.resize(6);
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: inputs has 6 values, expected 4"));

  parts = {Part(0), Part(1)};
  parts[1].images = {1, 2};
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: images has 2 values, expected 0"));

  parts = {Part(0), Part(1)};
  parts[1].rewards.pop_back();
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: rewards has 1 values, expected 2"));

  parts = {Part(0), Part(1)};
  parts[1].episode_starts.push_back(0);
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: episode_starts has 3 values, expected 2"));

  parts = {Part(0), Part(1)};
  parts[0].last_input.pop_back();
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 0: last_input has 1 values, expected 2"));
}

TEST(SlotRolloutTest, RefusesEventsOutsideTheRollout) {
  std::vector<SlotRollout> parts = {Part(0), Part(1)};
  parts[1].truncations = {Cut(2, 0)};
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: truncation at step 2 of a rollout of 2"));

  parts = {Part(0), Part(1)};
  parts[1].truncations = {{.step = 0, .input = {1}}};
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 1: truncation input has 1 values, expected 2"));

  parts = {Part(0), Part(1)};
  parts[0].finished = {{.step = -1}};
  EXPECT_THAT(MergeError(parts), HasSubstr("slot 0: finished episode at step -1"));
}

}  // namespace
}  // namespace dcs::actor
