// Copyright 2026 The DCS Authors.
#ifndef DCS_ACTOR_ROLLOUT_COLLECTOR_H_
#define DCS_ACTOR_ROLLOUT_COLLECTOR_H_

// Collects rollouts from a vector of scheduled environments with a policy, as
// Stable-Baselines3's collect_rollouts does (common/on_policy_algorithm.py): each step the policy
// samples an action per slot; the environment gets it clipped to the action bounds (continuous)
// while the rollout keeps the unclipped sample; episode starts are flagged; a step cut by the time
// limit and not terminated records its final observation for the learner to bootstrap.
//
// It also keeps, per slot, a journal of the running episode (its number, the global step of its
// reset, the actions so far): with deterministic environments that is all a resumed run needs to
// rebuild the slot exactly (VectorEnv::ReplaySlot).
//
// Randomness: slot s samples rollout r's actions from StreamSeed(run_seed, "actions", {s, r}),
// s being the slot's index in the run (DynamicContextEnv::slot_index), not its row in the
// VectorEnv. So a slot collected alone, in a VectorEnv of that one slot with the run's
// run_slots(), gives exactly its part of the rollout the whole run's collector gives
// (actor/slot_rollout.h merges the parts). Confined to one thread.

#include <algorithm>
#include <cstdint>
#include <span>
#include <type_traits>
#include <vector>

#include "actor/policy.h"
#include "actor/rollout.h"
#include "common/random.h"
#include "env/vector_env.h"

namespace dcs::actor {

// A slot's running episode, for replay on resume.
struct SlotJournal {
  int64_t episode = 0;            // the slot's episode number
  int64_t reset_step = 0;         // global environment step at its reset
  std::vector<float> actions;     // the actions sent to the environment so far
  double episode_return = 0;
};

// A finished training episode.
struct EpisodeSummary {
  double episode_return = 0;
  int64_t length = 0;
  int step = 0;  // the rollout step (0 .. num_steps - 1) whose transition ended it
};

// The policy's input for one slot: [observation, context] as floats (image environments: the
// context only, the observation going to `image`).
template <typename Env>
void AppendPolicyInput(std::span<const typename Env::Observation> observation,
                       std::span<const float> context, std::vector<float>& flat,
                       std::vector<uint8_t>& image) {
  if constexpr (std::is_same_v<typename Env::Observation, uint8_t>) {
    image.insert(image.end(), observation.begin(), observation.end());
  } else {
    flat.insert(flat.end(), observation.begin(), observation.end());
  }
  flat.insert(flat.end(), context.begin(), context.end());
}

// The action the environment receives for a policy action: an index, or clipped to the bounds.
template <typename Env>
void ToEnvAction(std::span<const float> action, std::span<typename Env::ActionElement> out) {
  if constexpr (std::is_integral_v<typename Env::ActionElement>) {
    out[0] = static_cast<typename Env::ActionElement>(action[0]);
  } else {
    for (int i = 0; i < Env::kActionSize; ++i) {
      out[i] = std::clamp(action[i], static_cast<float>(Env::kActionLow[i]),
                          static_cast<float>(Env::kActionHigh[i]));
    }
  }
}

template <typename Env>
class RolloutCollector {
 public:
  // Borrows `envs` (must outlive the collector). Resets every slot unless `journals` (one per
  // slot) is given, in which case each slot is replayed to where its journal left it.
  RolloutCollector(env::VectorEnv<Env>& envs, uint64_t run_seed,
                   std::vector<SlotJournal> journals = {})
      : envs_(envs), run_seed_(run_seed), journals_(std::move(journals)) {
    if (journals_.empty()) {
      envs_.Reset();
      journals_.resize(envs_.size());
      for (int i = 0; i < envs_.size(); ++i) journals_[i].episode = envs_.slot(i).episode();
    } else {
      for (int i = 0; i < envs_.size(); ++i) Replay(i);
    }
    // A slot whose episode has no action yet shows its episode's first observation.
    for (const SlotJournal& journal : journals_) {
      episode_starts_.push_back(journal.actions.empty());
    }
  }

  // Collects `n_steps` transitions of every slot with `policy` into `out` (replacing it) as
  // rollout number `rollout_index`; appends the episodes that finished to `finished`, by step,
  // then by row.
  void Collect(Policy& policy, int n_steps, int64_t rollout_index, Rollout& out,
               std::vector<EpisodeSummary>& finished);

  const std::vector<SlotJournal>& journals() const { return journals_; }

 private:
  void Replay(int slot);

  env::VectorEnv<Env>& envs_;
  const uint64_t run_seed_;
  std::vector<SlotJournal> journals_;
  std::vector<uint8_t> episode_starts_;  // the next observation starts an episode
};

// Implementation details.

template <typename Env>
void RolloutCollector<Env>::Replay(int slot) {
  const SlotJournal& journal = journals_[slot];
  std::vector<typename Env::ActionElement> actions(journal.actions.begin(), journal.actions.end());
  envs_.ReplaySlot(slot, journal.episode, journal.reset_step, actions);
}

template <typename Env>
void RolloutCollector<Env>::Collect(Policy& policy, int n_steps, int64_t rollout_index,
                                    Rollout& out, std::vector<EpisodeSummary>& finished) {
  constexpr int kObs = Env::kObservationSize;
  constexpr int kAct = Env::kActionSize;
  const int slots = envs_.size();
  const int context_size = envs_.context_size();
  out = Rollout{.num_steps = n_steps, .num_envs = slots};
  std::vector<Random> randoms;
  for (int i = 0; i < slots; ++i) {
    randoms.emplace_back(StreamSeed(run_seed_, "actions",
                                    {envs_.slot(i).slot_index(),
                                     static_cast<uint64_t>(rollout_index)}));
  }
  std::vector<float> actions(static_cast<size_t>(slots) * kAct);
  std::vector<typename Env::ActionElement> env_actions(actions.size());
  for (int t = 0; t < n_steps; ++t) {
    // Every slot's input goes into the rollout, and from there to the policy, in one batch.
    const size_t first_input = out.inputs.size();
    const size_t first_image = out.images.size();
    for (int i = 0; i < slots; ++i) {
      AppendPolicyInput<Env>(
          envs_.observations().subspan(static_cast<size_t>(i) * kObs, kObs),
          envs_.contexts().subspan(static_cast<size_t>(i) * context_size, context_size),
          out.inputs, out.images);
    }
    policy.Act(slots, std::span<const float>(out.inputs).subspan(first_input),
               std::span<const uint8_t>(out.images).subspan(first_image),
               /*deterministic=*/false, randoms, actions);
    out.actions.insert(out.actions.end(), actions.begin(), actions.end());
    for (int i = 0; i < slots; ++i) {
      out.episode_starts.push_back(episode_starts_[i]);
      ToEnvAction<Env>(std::span<const float>(actions).subspan(static_cast<size_t>(i) * kAct, kAct),
                       std::span(env_actions).subspan(static_cast<size_t>(i) * kAct, kAct));
    }
    const int64_t next_reset_step = envs_.global_steps() + envs_.run_slots();
    envs_.Step(env_actions);
    for (int i = 0; i < slots; ++i) {
      const float reward = envs_.rewards()[i];
      out.rewards.push_back(reward);
      SlotJournal& journal = journals_[i];
      journal.episode_return += reward;
      journal.actions.insert(journal.actions.end(), env_actions.begin() + i * kAct,
                             env_actions.begin() + (i + 1) * kAct);
      const bool terminated = envs_.terminated()[i];
      const bool truncated = envs_.truncated()[i];
      episode_starts_[i] = terminated || truncated;
      if (!episode_starts_[i]) continue;
      if (truncated && !terminated) {
        Rollout::Truncation cut{.step = t, .env = i};
        AppendPolicyInput<Env>(
            envs_.final_observations().subspan(static_cast<size_t>(i) * kObs, kObs),
            envs_.final_contexts().subspan(static_cast<size_t>(i) * context_size, context_size),
            cut.input, cut.image);
        out.truncations.push_back(std::move(cut));
      }
      finished.push_back({.episode_return = journal.episode_return,
                          .length = static_cast<int64_t>(journal.actions.size() / kAct),
                          .step = t});
      journal = SlotJournal{.episode = envs_.slot(i).episode(), .reset_step = next_reset_step};
    }
  }
  for (int i = 0; i < slots; ++i) {
    AppendPolicyInput<Env>(
        envs_.observations().subspan(static_cast<size_t>(i) * kObs, kObs),
        envs_.contexts().subspan(static_cast<size_t>(i) * context_size, context_size),
        out.last_inputs, out.last_images);
    out.last_dones.push_back(episode_starts_[i]);
  }
}

}  // namespace dcs::actor

#endif  // DCS_ACTOR_ROLLOUT_COLLECTOR_H_
