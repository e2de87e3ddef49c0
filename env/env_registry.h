// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_ENV_REGISTRY_H_
#define DCS_ENV_ENV_REGISTRY_H_

// The environments by name, for code that picks one at run time (configs, `dcs env ...`):
//
//   absl::Status status = VisitEnvironment(name, [&]<typename Env>() -> absl::Status {
//     return RunWith<Env>(...);
//   });
//
// Thread-safe.

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/string_view.h"
#include "env/bipedal_walker.h"
#include "env/car_racing.h"
#include "env/cartpole.h"

namespace dcs::env {

// Every environment's name, as configs spell it.
inline std::vector<std::string> EnvironmentNames() {
  return {std::string(CartPole::kName), std::string(BipedalWalker::kName),
          std::string(CarRacing::kName), std::string(CarRacingDiscrete::kName)};
}

// Calls `visitor.template operator()<Env>()` with the environment class called `name` and
// returns its status. INVALID_ARGUMENT, listing the known names, for an unknown name.
template <typename Visitor>
absl::Status VisitEnvironment(absl::string_view name, Visitor&& visitor) {
  if (name == CartPole::kName) return visitor.template operator()<CartPole>();
  if (name == BipedalWalker::kName) return visitor.template operator()<BipedalWalker>();
  if (name == CarRacing::kName) return visitor.template operator()<CarRacing>();
  if (name == CarRacingDiscrete::kName) return visitor.template operator()<CarRacingDiscrete>();
  return absl::InvalidArgumentError(absl::StrCat("unknown environment '", name, "' (known: ",
                                                 absl::StrJoin(EnvironmentNames(), ", "), ")"));
}

}  // namespace dcs::env

#endif  // DCS_ENV_ENV_REGISTRY_H_
