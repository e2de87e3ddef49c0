// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_BASELINE_POLICIES_H_
#define DCS_ENV_BASELINE_POLICIES_H_

// The baseline policies by name (env/baseline_policy.h): "random" for every environment,
// "heuristic" for bipedal_walker, "centerline" for car_racing. Thread-safe.

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "env/baseline_policy.h"

namespace dcs::env {

// The policies available for Env.
template <typename Env>
std::vector<std::string> BaselinePolicyNames() {
  return {"random"};
}

// The policy called `name` for Env; `seed` seeds its randomness if it has any.
// INVALID_ARGUMENT, listing the available ones, if Env has no such policy.
template <typename Env>
absl::StatusOr<std::unique_ptr<BaselinePolicy<Env>>> MakeBaselinePolicy(absl::string_view name,
                                                                        uint64_t seed) {
  if (name == "random") return std::make_unique<RandomPolicy<Env>>(seed);
  return absl::InvalidArgumentError(absl::StrCat("no baseline policy '", name, "' for ",
                                                 Env::kName, " (available: ",
                                                 absl::StrJoin(BaselinePolicyNames<Env>(), ", "),
                                                 ")"));
}

}  // namespace dcs::env

#endif  // DCS_ENV_BASELINE_POLICIES_H_
