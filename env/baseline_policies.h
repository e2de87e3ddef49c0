// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BASELINE_POLICIES_H_
#define DCS_ENV_BASELINE_POLICIES_H_

// The baseline policies by name (env/baseline_policy.h): "random" for every environment,
// "heuristic" (Gymnasium's walker controller) for bipedal_walker, "centerline" (a scripted
// driver) for car_racing. Thread-safe.

#include <algorithm>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "env/baseline_policy.h"
#include "env/bipedal_walker.h"
#include "env/bipedal_walker_heuristic.h"
#include "env/car_racing.h"
#include "env/car_racing_centerline.h"

namespace dcs::env {

// Gymnasium's heuristic driver: a zero action first, then the controller on each observation.
class WalkerHeuristicPolicy final : public BaselinePolicy<BipedalWalker> {
 public:
  void Reset(const BipedalWalker& /*env*/) override {
    heuristic_.Reset();
    first_ = true;
  }
  void Act(const BipedalWalker& /*env*/, ObservationSpan observation, ActionSpan action) override {
    if (std::exchange(first_, false)) {
      std::fill(action.begin(), action.end(), 0.0f);
      return;
    }
    const std::array<float, 4> chosen = heuristic_.Act(observation);
    std::copy(chosen.begin(), chosen.end(), action.begin());
  }

 private:
  WalkerHeuristic heuristic_;
  bool first_ = true;
};

class CenterlinePolicy final : public BaselinePolicy<CarRacing> {
 public:
  void Reset(const CarRacing& env) override { driver_.Reset(env); }
  void Act(const CarRacing& env, ObservationSpan /*observation*/, ActionSpan action) override {
    driver_.Act(env, action);
  }

 private:
  CenterlineDriver driver_;
};

// The policies available for Env.
template <typename Env>
std::vector<std::string> BaselinePolicyNames() {
  if constexpr (std::is_same_v<Env, BipedalWalker>) return {"random", "heuristic"};
  if constexpr (std::is_same_v<Env, CarRacing>) return {"random", "centerline"};
  return {"random"};
}

// The policy called `name` for Env; `seed` seeds its randomness if it has any.
// INVALID_ARGUMENT, listing the available ones, if Env has no such policy.
template <typename Env>
absl::StatusOr<std::unique_ptr<BaselinePolicy<Env>>> MakeBaselinePolicy(absl::string_view name,
                                                                        uint64_t seed) {
  if (name == "random") return std::make_unique<RandomPolicy<Env>>(seed);
  if constexpr (std::is_same_v<Env, BipedalWalker>) {
    if (name == "heuristic") return std::make_unique<WalkerHeuristicPolicy>();
  }
  if constexpr (std::is_same_v<Env, CarRacing>) {
    if (name == "centerline") return std::make_unique<CenterlinePolicy>();
  }
  return absl::InvalidArgumentError(absl::StrCat("no baseline policy '", name, "' for ",
                                                 Env::kName, " (available: ",
                                                 absl::StrJoin(BaselinePolicyNames<Env>(), ", "),
                                                 ")"));
}

}  // namespace dcs::env

#endif  // DCS_ENV_BASELINE_POLICIES_H_
