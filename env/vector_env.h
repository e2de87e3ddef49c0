// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_VECTOR_ENV_H_
#define DCS_ENV_VECTOR_ENV_H_

// N dynamic-context environment slots stepped as one batch, with struct-of-arrays buffers:
// the shape actors and evaluation consume. Row i of every buffer belongs to slot i.
//
// Auto-reset, as Stable-Baselines3's vectorised environments do it: when slot i's episode ends
// (terminated or truncated), its last observation and context go to final_observations() and
// final_contexts() (needed to bootstrap the value of a time-limit cut) and the slot resets at
// once, so observations() holds the next episode's first observation. Rows of slots that did
// not finish leave their final_* rows unspecified.
//
// The batch may hold a subset of a run's slots (each slot keeps its run index in
// DynamicContextOptions::slot, which keys its randomness). The environment-step count is the
// run's: every Step advances it by run_slots(), the number of slots of the whole run, however
// many of them this batch holds. Multi-stage schedules switch stage by that count
// (env/staged_schedule.h), so a slot stepped alone, with run_slots() the run's, sees the stage
// switches it would see in the full batch. Confined to one thread.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "env/dynamic_context_env.h"

namespace dcs::env {

template <typename Env>
class VectorEnv {
 public:
  using Observation = typename Env::Observation;
  using ActionElement = typename Env::ActionElement;
  static constexpr int kObservationSize = Env::kObservationSize;
  static constexpr int kActionSize = Env::kActionSize;

  // One options per slot; every slot must observe the same number of context values.
  // `run_slots` is the number of slots of the whole run; 0 means size() (the batch is the run).
  // Errors as DynamicContextEnv::Create, naming the slot; INVALID_ARGUMENT for a run_slots
  // that is negative or below size().
  static absl::StatusOr<VectorEnv> Create(std::vector<DynamicContextOptions> slots,
                                          int run_slots = 0);

  int size() const { return static_cast<int>(slots_.size()); }
  // The number of slots of the whole run: what each Step adds to global_steps().
  int run_slots() const { return run_slots_; }
  int context_size() const { return context_size_; }
  // Environment steps of the run so far (not of this batch alone).
  int64_t global_steps() const { return global_steps_; }

  // Starts an episode in every slot.
  void Reset();

  // One step of every slot; `actions` holds size() x kActionSize elements, row by row. A slot
  // whose episode ends resets at global step global_steps() + run_slots(), the run's count
  // after this step; then global_steps() advances by run_slots().
  void Step(std::span<const ActionElement> actions);

  std::span<const Observation> observations() const { return observations_; }
  std::span<const float> contexts() const { return contexts_; }
  std::span<const float> rewards() const { return rewards_; }
  std::span<const uint8_t> terminated() const { return terminated_; }
  std::span<const uint8_t> truncated() const { return truncated_; }
  std::span<const Observation> final_observations() const { return final_observations_; }
  std::span<const float> final_contexts() const { return final_contexts_; }

  DynamicContextEnv<Env>& slot(int i) { return slots_[i]; }

  // Puts slot `i` back where a run left it: episode `episode`, reset at global step
  // `reset_step`, then `actions` (kActionSize elements each) applied in order. Environments
  // are deterministic, so this reproduces the slot's state exactly; its observation and
  // context rows are rewritten. REQUIRES: the actions do not end the episode.
  void ReplaySlot(int i, int64_t episode, int64_t reset_step,
                  std::span<const ActionElement> actions);

  // Sets the run's environment-step count (a resumed run, or a slot rebuilt on another
  // process, continues the run's count).
  void set_global_steps(int64_t steps) { global_steps_ = steps; }

 private:
  VectorEnv(std::vector<DynamicContextEnv<Env>> slots, int run_slots, int context_size)
      : slots_(std::move(slots)),
        run_slots_(run_slots),
        context_size_(context_size),
        observations_(slots_.size() * kObservationSize),
        contexts_(slots_.size() * context_size),
        rewards_(slots_.size()),
        terminated_(slots_.size()),
        truncated_(slots_.size()),
        final_observations_(slots_.size() * kObservationSize),
        final_contexts_(slots_.size() * context_size) {}

  std::span<Observation, kObservationSize> ObservationRow(std::vector<Observation>& rows, int i) {
    return std::span<Observation, kObservationSize>(rows.data() + i * kObservationSize,
                                                    kObservationSize);
  }
  std::span<float> ContextRow(std::vector<float>& rows, int i) {
    return std::span<float>(rows).subspan(i * context_size_, context_size_);
  }

  std::vector<DynamicContextEnv<Env>> slots_;
  const int run_slots_;
  const int context_size_;
  int64_t global_steps_ = 0;
  std::vector<Observation> observations_;
  std::vector<float> contexts_;
  std::vector<float> rewards_;
  std::vector<uint8_t> terminated_;
  std::vector<uint8_t> truncated_;
  std::vector<Observation> final_observations_;
  std::vector<float> final_contexts_;
};

// Implementation details.

template <typename Env>
absl::StatusOr<VectorEnv<Env>> VectorEnv<Env>::Create(std::vector<DynamicContextOptions> slots,
                                                      int run_slots) {
  if (slots.empty()) return absl::InvalidArgumentError("a vector of environments needs a slot");
  if (run_slots == 0) run_slots = static_cast<int>(slots.size());
  if (run_slots < static_cast<int>(slots.size())) {
    return absl::InvalidArgumentError(absl::StrCat("a run of ", run_slots,
                                                   " slots cannot hold a batch of ",
                                                   slots.size()));
  }
  std::vector<DynamicContextEnv<Env>> envs;
  envs.reserve(slots.size());
  for (size_t i = 0; i < slots.size(); ++i) {
    absl::StatusOr<DynamicContextEnv<Env>> env =
        DynamicContextEnv<Env>::Create(std::move(slots[i]));
    if (!env.ok()) {
      return absl::InvalidArgumentError(absl::StrCat("slot ", i, ": ", env.status().message()));
    }
    envs.push_back(*std::move(env));
  }
  const int context_size = envs[0].context_size();
  for (size_t i = 1; i < envs.size(); ++i) {
    if (envs[i].context_size() != context_size) {
      return absl::InvalidArgumentError(absl::StrCat(
          "slot ", i, " observes ", envs[i].context_size(), " context values, slot 0 ",
          context_size, ": every slot must observe the same"));
    }
  }
  return VectorEnv(std::move(envs), run_slots, context_size);
}

template <typename Env>
void VectorEnv<Env>::ReplaySlot(int i, int64_t episode, int64_t reset_step,
                                std::span<const ActionElement> actions) {
  const std::span<Observation, kObservationSize> observation = ObservationRow(observations_, i);
  const std::span<float> context = ContextRow(contexts_, i);
  slots_[i].SetNextEpisode(episode);
  slots_[i].Reset(reset_step, observation, context);
  for (size_t at = 0; at + kActionSize <= actions.size(); at += kActionSize) {
    slots_[i].Step(std::span<const ActionElement, kActionSize>(actions.data() + at, kActionSize),
                   observation, context);
  }
}

template <typename Env>
void VectorEnv<Env>::Reset() {
  for (int i = 0; i < size(); ++i) {
    slots_[i].Reset(global_steps_, ObservationRow(observations_, i), ContextRow(contexts_, i));
  }
}

template <typename Env>
void VectorEnv<Env>::Step(std::span<const ActionElement> actions) {
  for (int i = 0; i < size(); ++i) {
    const std::span<Observation, kObservationSize> observation = ObservationRow(observations_, i);
    const std::span<float> context = ContextRow(contexts_, i);
    const StepResult result = slots_[i].Step(
        std::span<const ActionElement, kActionSize>(actions.data() + i * kActionSize,
                                                    kActionSize),
        observation, context);
    rewards_[i] = static_cast<float>(result.reward);
    terminated_[i] = result.terminated;
    truncated_[i] = result.truncated;
    if (result.done()) {
      // Copies, not memcpy: a context-free env's context rows are empty, with null data().
      std::ranges::copy(observation, ObservationRow(final_observations_, i).begin());
      std::ranges::copy(context, ContextRow(final_contexts_, i).begin());
      slots_[i].Reset(global_steps_ + run_slots_, observation, context);
    }
  }
  global_steps_ += run_slots_;
}

}  // namespace dcs::env

#endif  // DCS_ENV_VECTOR_ENV_H_
