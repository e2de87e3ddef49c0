// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_SLOT_ROLLOUT_H_
#define DCS_ACTOR_SLOT_ROLLOUT_H_

// One environment slot's part of a rollout, as a process that steps that slot alone delivers
// it, and the merge that puts a run's parts back together. A part comes from a
// RolloutCollector over a VectorEnv of that one slot whose run_slots() is the run's
// (actor/rollout_collector.h); merging every slot's part of rollout r gives exactly, bit for
// bit, the Rollout, finished-episode list and journals that one collector over all the run's
// slots gives for rollout r. Thread-compatible (plain data and pure functions).

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/rollout.h"
#include "actor/rollout_collector.h"

namespace dcs::actor {

// Slot `slot`'s num_steps transitions of one rollout: Rollout's fields for one slot, so
// [t][...] where Rollout has [t][e][...].
struct SlotRollout {
  int slot = 0;  // the slot's index in the run (DynamicContextOptions::slot)
  int num_steps = 0;
  std::vector<float> inputs;            // [t][flat_input_size]
  std::vector<uint8_t> images;          // [t][height * width * channels]; empty without images
  std::vector<float> actions;           // [t][action_size], unclipped samples
  std::vector<float> rewards;           // [t]
  std::vector<uint8_t> episode_starts;  // [t]
  // The slot's steps cut by the time limit, by step. `env` is ignored: merging sets the slot.
  std::vector<Rollout::Truncation> truncations;
  // After the last step: the slot's next input and whether that step ended its episode.
  std::vector<float> last_input;
  std::vector<uint8_t> last_image;
  bool last_done = false;
  std::vector<EpisodeSummary> finished;  // the episodes that ended in this rollout, by step
  SlotJournal journal;                   // the slot's running episode after this rollout
};

// Slot `slot`'s part, from `one_slot` (what RolloutCollector::Collect fills for a VectorEnv of
// that slot alone), the episodes that finished in it and the slot's journal after it.
// REQUIRES: one_slot.num_envs == 1.
SlotRollout MakeSlotRollout(Rollout one_slot, int slot, std::vector<EpisodeSummary> finished,
                            SlotJournal journal);

// The sizes of one slot's part: num_steps steps of rows of these sizes.
struct SlotRolloutShape {
  int num_steps = 0;
  size_t input = 0;   // floats per step
  size_t image = 0;   // bytes per step
  size_t action = 0;  // floats per step
};

// OK if `part` has `shape`: its num_steps, rows of its sizes, one reward and one episode start
// per step, a last input and image of one row, and truncations (of one row) and finished
// episodes at steps inside the rollout. INVALID_ARGUMENT naming the slot and the field
// otherwise.
absl::Status CheckSlotRollout(const SlotRollout& part, const SlotRolloutShape& shape);

// A run's rollout put back together from its slots' parts.
struct MergedRollout {
  Rollout rollout;
  std::vector<EpisodeSummary> finished;  // by step, then slot, as the collector appends them
  std::vector<SlotJournal> journals;     // by slot
};

// Merges the parts of one rollout of a run of slots.size() slots, given in any order: slot e's
// part becomes column e of the rollout; truncations and finished episodes are ordered by step,
// then slot, as RolloutCollector::Collect orders them.
// INVALID_ARGUMENT, naming the slot and the field, unless the parts are slots 0 .. n-1 once
// each and all have slot 0's shape (num_steps above 0; inputs, images and actions divided by
// num_steps) as CheckSlotRollout checks it.
absl::StatusOr<MergedRollout> MergeSlotRollouts(std::vector<SlotRollout> slots);

}  // namespace dcs::actor

#endif  // DCS_ACTOR_SLOT_ROLLOUT_H_
