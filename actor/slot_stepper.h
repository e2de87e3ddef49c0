// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_SLOT_STEPPER_H_
#define DCS_ACTOR_SLOT_STEPPER_H_

// One env slot of a run, stepped alone (by an actor holding the slot's lease): it collects the
// slot's part of each rollout (actor/slot_rollout.h) and can be rebuilt, exactly, from the
// slot's journal at any rollout boundary, so whichever process steps a slot, and however often
// the slot changes hands, its parts are the ones one process stepping every slot would give.
//
//   positioned_at() == -1 ─ Rebuild(journal, r, start) ─▶ positioned at r
//   Collect(policy) ─▶ the slot's part of rollout r; positioned at r + 1
//
// Confined to one thread.

#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

#include "absl/status/statusor.h"
#include "actor/policy.h"
#include "actor/rollout_collector.h"
#include "actor/slot_rollout.h"
#include "common/status_macros.h"
#include "env/dynamic_context_env.h"
#include "env/vector_env.h"

namespace dcs::actor {

class SlotStepper {
 public:
  virtual ~SlotStepper() = default;

  // The rollout the slot stands before, or -1 if it has not been built.
  int64_t positioned_at() const { return positioned_at_; }

  // Rebuilds the slot as `journal` says it stood before rollout `rollout`, the run having
  // taken `start_timesteps` environment steps by then.
  virtual void Rebuild(const SlotJournal& journal, int64_t rollout, int64_t start_timesteps) = 0;

  // Collects the slot's part of rollout positioned_at() with `policy` (which must be that
  // rollout's policy version). REQUIRES: positioned_at() >= 0.
  virtual SlotRollout Collect(Policy& policy, int n_steps) = 0;

 protected:
  int64_t positioned_at_ = -1;
};

// A stepper of `Env` for slot `options.slot` of a run of `run_slots` slots (seeded
// `options.run_seed`). Errors as DynamicContextEnv::Create.
template <typename Env>
absl::StatusOr<std::unique_ptr<SlotStepper>> MakeSlotStepper(env::DynamicContextOptions options,
                                                             int run_slots);

// Implementation details.

namespace slot_stepper_internal {

template <typename Env>
class EnvSlotStepper final : public SlotStepper {
 public:
  EnvSlotStepper(env::DynamicContextOptions options, int run_slots)
      : options_(std::move(options)), run_slots_(run_slots) {}

  // Builds the environment once, to report a bad option at creation.
  absl::Status Check() const { return NewEnvs().status(); }

  void Rebuild(const SlotJournal& journal, int64_t rollout, int64_t start_timesteps) override {
    collector_.reset();
    // Check() succeeded on the same options, so this cannot fail.
    envs_ = std::make_unique<env::VectorEnv<Env>>(*NewEnvs());
    envs_->set_global_steps(start_timesteps);
    collector_ = std::make_unique<RolloutCollector<Env>>(*envs_, options_.run_seed,
                                                         std::vector<SlotJournal>{journal});
    positioned_at_ = rollout;
  }

  SlotRollout Collect(Policy& policy, int n_steps) override {
    Rollout rollout;
    std::vector<EpisodeSummary> finished;
    collector_->Collect(policy, n_steps, positioned_at_, rollout, finished);
    ++positioned_at_;
    return MakeSlotRollout(std::move(rollout), static_cast<int>(options_.slot),
                           std::move(finished), collector_->journals()[0]);
  }

 private:
  absl::StatusOr<env::VectorEnv<Env>> NewEnvs() const {
    return env::VectorEnv<Env>::Create({options_}, run_slots_);
  }

  const env::DynamicContextOptions options_;
  const int run_slots_;
  std::unique_ptr<env::VectorEnv<Env>> envs_;
  std::unique_ptr<RolloutCollector<Env>> collector_;  // borrows *envs_
};

}  // namespace slot_stepper_internal

template <typename Env>
absl::StatusOr<std::unique_ptr<SlotStepper>> MakeSlotStepper(env::DynamicContextOptions options,
                                                             int run_slots) {
  auto stepper = std::make_unique<slot_stepper_internal::EnvSlotStepper<Env>>(std::move(options),
                                                                              run_slots);
  DCS_RETURN_IF_ERROR(stepper->Check());
  return stepper;
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_SLOT_STEPPER_H_
