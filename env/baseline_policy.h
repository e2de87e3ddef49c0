// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BASELINE_POLICY_H_
#define DCS_ENV_BASELINE_POLICY_H_

// Baseline policies every RL user compares a trained policy against: uniformly random actions
// (any environment), Gymnasium's heuristic walker controller (BipedalWalker) and a scripted
// centre-line driver (CarRacing). `dcs env rollout` and `dcs env render` run them.
// Confined to one thread; one instance per environment.

#include <cstdint>
#include <memory>
#include <span>
#include <type_traits>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "common/random.h"

namespace dcs::env {

template <typename Env>
class BaselinePolicy {
 public:
  using ObservationSpan = std::span<const typename Env::Observation, Env::kObservationSize>;
  using ActionSpan = std::span<typename Env::ActionElement, Env::kActionSize>;

  virtual ~BaselinePolicy() = default;

  // Called after every reset of `env`.
  virtual void Reset(const Env& env) = 0;
  // Writes the action to take in `env`, which shows `observation`.
  virtual void Act(const Env& env, ObservationSpan observation, ActionSpan action) = 0;
};

// Uniform actions: a discrete action from [0, kNumActions), or each continuous component from
// [kActionLow[i], kActionHigh[i]].
template <typename Env>
class RandomPolicy final : public BaselinePolicy<Env> {
 public:
  explicit RandomPolicy(uint64_t seed) : random_(seed) {}

  void Reset(const Env& /*env*/) override {}

  void Act(const Env& /*env*/, typename BaselinePolicy<Env>::ObservationSpan /*observation*/,
           typename BaselinePolicy<Env>::ActionSpan action) override {
    if constexpr (std::is_integral_v<typename Env::ActionElement>) {
      action[0] = static_cast<typename Env::ActionElement>(random_.Integers(0, Env::kNumActions));
    } else {
      for (int i = 0; i < Env::kActionSize; ++i) {
        action[i] = static_cast<float>(random_.Uniform(Env::kActionLow[i], Env::kActionHigh[i]));
      }
    }
  }

 private:
  Random random_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_BASELINE_POLICY_H_
