// Copyright 2026 The DCS Authors.
#include "actor/slot_rollout.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "common/status_macros.h"

namespace dcs::actor {
namespace {

absl::Status CheckSize(int slot, absl::string_view field, size_t size, size_t expected) {
  if (size == expected) return absl::OkStatus();
  return absl::InvalidArgumentError(
      absl::StrCat("slot ", slot, ": ", field, " has ", size, " values, expected ", expected));
}

// The parts sorted by slot must be slots 0 .. n-1.
absl::Status CheckSlotIndices(const std::vector<SlotRollout>& by_slot) {
  const int n = static_cast<int>(by_slot.size());
  for (int i = 0; i < n; ++i) {
    const int slot = by_slot[i].slot;
    if (slot == i) continue;
    if (slot < 0) return absl::InvalidArgumentError(absl::StrCat("slot ", slot, " is negative"));
    if (i > 0 && slot == by_slot[i - 1].slot) {
      return absl::InvalidArgumentError(absl::StrCat("slot ", slot, " is given twice"));
    }
    return absl::InvalidArgumentError(
        absl::StrCat("slot ", i, " is missing: ", n, " parts need slots 0 to ", n - 1));
  }
  return absl::OkStatus();
}

// A row size: `size` values over `num_steps` steps of `slot`'s `field`.
absl::StatusOr<size_t> RowSize(int slot, absl::string_view field, size_t size, int num_steps) {
  if (size % num_steps != 0) {
    return absl::InvalidArgumentError(absl::StrCat("slot ", slot, ": ", field, " has ", size,
                                                   " values, not a multiple of ", num_steps,
                                                   " steps"));
  }
  return size / num_steps;
}

// The shape every part must share, from slot 0's part.
absl::StatusOr<SlotRolloutShape> ShapeOf(const SlotRollout& first) {
  if (first.num_steps <= 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("slot ", first.slot, ": num_steps is ", first.num_steps));
  }
  SlotRolloutShape shape{.num_steps = first.num_steps};
  DCS_ASSIGN_OR_RETURN(shape.input,
                       RowSize(first.slot, "inputs", first.inputs.size(), first.num_steps));
  DCS_ASSIGN_OR_RETURN(shape.image,
                       RowSize(first.slot, "images", first.images.size(), first.num_steps));
  DCS_ASSIGN_OR_RETURN(shape.action,
                       RowSize(first.slot, "actions", first.actions.size(), first.num_steps));
  return shape;
}

// The per-step fields and the last row.
absl::Status CheckSteps(const SlotRollout& part, const SlotRolloutShape& shape) {
  if (part.num_steps != shape.num_steps) {
    return absl::InvalidArgumentError(absl::StrCat("slot ", part.slot, ": num_steps is ",
                                                   part.num_steps, ", expected ",
                                                   shape.num_steps));
  }
  const size_t steps = static_cast<size_t>(shape.num_steps);
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "inputs", part.inputs.size(), steps * shape.input));
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "images", part.images.size(), steps * shape.image));
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "actions", part.actions.size(), steps * shape.action));
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "rewards", part.rewards.size(), steps));
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "episode_starts", part.episode_starts.size(), steps));
  DCS_RETURN_IF_ERROR(CheckSize(part.slot, "last_input", part.last_input.size(), shape.input));
  return CheckSize(part.slot, "last_image", part.last_image.size(), shape.image);
}

absl::Status CheckStep(int slot, absl::string_view field, int step, int num_steps) {
  if (step >= 0 && step < num_steps) return absl::OkStatus();
  return absl::InvalidArgumentError(absl::StrCat("slot ", slot, ": ", field, " at step ", step,
                                                 " of a rollout of ", num_steps, " steps"));
}

// The truncations and the finished episodes.
absl::Status CheckEvents(const SlotRollout& part, const SlotRolloutShape& shape) {
  for (const Rollout::Truncation& cut : part.truncations) {
    DCS_RETURN_IF_ERROR(CheckStep(part.slot, "truncation", cut.step, shape.num_steps));
    DCS_RETURN_IF_ERROR(CheckSize(part.slot, "truncation input", cut.input.size(), shape.input));
    DCS_RETURN_IF_ERROR(CheckSize(part.slot, "truncation image", cut.image.size(), shape.image));
  }
  for (const EpisodeSummary& episode : part.finished) {
    DCS_RETURN_IF_ERROR(CheckStep(part.slot, "finished episode", episode.step, shape.num_steps));
  }
  return absl::OkStatus();
}

template <typename T>
void AppendRow(const std::vector<T>& rows, int t, size_t width, std::vector<T>& out) {
  const auto begin = rows.begin() + static_cast<std::ptrdiff_t>(t * width);
  out.insert(out.end(), begin, begin + static_cast<std::ptrdiff_t>(width));
}

// The per-step fields, [t][e] with part e as column e.
void InterleaveSteps(const std::vector<SlotRollout>& by_slot, const SlotRolloutShape& shape,
                     Rollout& out) {
  for (int t = 0; t < shape.num_steps; ++t) {
    for (const SlotRollout& part : by_slot) {
      AppendRow(part.inputs, t, shape.input, out.inputs);
      AppendRow(part.images, t, shape.image, out.images);
      AppendRow(part.actions, t, shape.action, out.actions);
      out.rewards.push_back(part.rewards[t]);
      out.episode_starts.push_back(part.episode_starts[t]);
    }
  }
}

void AppendLastRows(const std::vector<SlotRollout>& by_slot, Rollout& out) {
  for (const SlotRollout& part : by_slot) {
    out.last_inputs.insert(out.last_inputs.end(), part.last_input.begin(), part.last_input.end());
    out.last_images.insert(out.last_images.end(), part.last_image.begin(), part.last_image.end());
    out.last_dones.push_back(part.last_done);
  }
}

// Every part's truncations, by step, then slot (each part's are by step already).
std::vector<Rollout::Truncation> MergeTruncations(std::vector<SlotRollout>& by_slot) {
  std::vector<Rollout::Truncation> merged;
  for (SlotRollout& part : by_slot) {
    for (Rollout::Truncation& cut : part.truncations) {
      cut.env = part.slot;
      merged.push_back(std::move(cut));
    }
  }
  std::stable_sort(
      merged.begin(), merged.end(),
      [](const Rollout::Truncation& a, const Rollout::Truncation& b) { return a.step < b.step; });
  return merged;
}

// Every part's finished episodes, by step, then slot.
std::vector<EpisodeSummary> MergeFinished(const std::vector<SlotRollout>& by_slot) {
  std::vector<EpisodeSummary> merged;
  for (const SlotRollout& part : by_slot) {
    merged.insert(merged.end(), part.finished.begin(), part.finished.end());
  }
  std::stable_sort(
      merged.begin(), merged.end(),
      [](const EpisodeSummary& a, const EpisodeSummary& b) { return a.step < b.step; });
  return merged;
}

}  // namespace

SlotRollout MakeSlotRollout(Rollout one_slot, int slot, std::vector<EpisodeSummary> finished,
                            SlotJournal journal) {
  assert(one_slot.num_envs == 1);
  return SlotRollout{.slot = slot,
                     .num_steps = one_slot.num_steps,
                     .inputs = std::move(one_slot.inputs),
                     .images = std::move(one_slot.images),
                     .actions = std::move(one_slot.actions),
                     .rewards = std::move(one_slot.rewards),
                     .episode_starts = std::move(one_slot.episode_starts),
                     .truncations = std::move(one_slot.truncations),
                     .last_input = std::move(one_slot.last_inputs),
                     .last_image = std::move(one_slot.last_images),
                     .last_done = one_slot.last_dones.front() != 0,
                     .finished = std::move(finished),
                     .journal = std::move(journal)};
}

absl::Status CheckSlotRollout(const SlotRollout& part, const SlotRolloutShape& shape) {
  DCS_RETURN_IF_ERROR(CheckSteps(part, shape));
  return CheckEvents(part, shape);
}

absl::StatusOr<MergedRollout> MergeSlotRollouts(std::vector<SlotRollout> slots) {
  if (slots.empty()) return absl::InvalidArgumentError("a rollout needs a slot");
  std::sort(slots.begin(), slots.end(),
            [](const SlotRollout& a, const SlotRollout& b) { return a.slot < b.slot; });
  DCS_RETURN_IF_ERROR(CheckSlotIndices(slots));
  DCS_ASSIGN_OR_RETURN(const SlotRolloutShape shape, ShapeOf(slots.front()));
  for (const SlotRollout& part : slots) DCS_RETURN_IF_ERROR(CheckSlotRollout(part, shape));
  MergedRollout merged{
      .rollout = {.num_steps = shape.num_steps, .num_envs = static_cast<int>(slots.size())}};
  InterleaveSteps(slots, shape, merged.rollout);
  AppendLastRows(slots, merged.rollout);
  merged.rollout.truncations = MergeTruncations(slots);
  merged.finished = MergeFinished(slots);
  for (SlotRollout& part : slots) merged.journals.push_back(std::move(part.journal));
  return merged;
}

}  // namespace dcs::actor
