// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_CONTEXT_FLAGS_H_
#define DCS_SERVICES_CLI_CONTEXT_FLAGS_H_

// Context features set on the command line, FEATURE=VALUE (`dcs env --set`, `dcs play
// --context`), checked as `dcs train` checks a config's `context`, with the same messages
// (env::ContextSpace::WithValues, Env::ValidateContext). Thread-safe (no state).

#include <map>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/context_feature.h"
#include "services/cli/cli_command.h"

namespace dcs::services::cli {

// `base` (every feature of Env, by index) with `values` (flag `flag`'s assignments, parsed by
// ParseAssignments) in place. INVALID_ARGUMENT prefixed with `flag` for an unknown feature, a
// value outside its feature's range, or a context Env refuses as a whole.
template <typename Env>
absl::StatusOr<std::vector<double>> ContextWithAssignments(
    std::vector<double> base, const std::map<std::string, double>& values,
    absl::string_view flag) {
  const env::ContextSpace& space = Env::Features();
  // Names and ranges, one feature at a time, with the messages a config's context gets.
  if (absl::StatusOr<std::vector<double>> checked = space.WithValues(values); !checked.ok()) {
    return Annotate(checked.status(), flag);
  }
  for (const auto& [name, value] : values) {
    DCS_ASSIGN_OR_RETURN(const int index, space.IndexOf(name));
    base[index] = value;
  }
  if (absl::Status whole = Env::ValidateContext(base); !whole.ok()) return Annotate(whole, flag);
  return base;
}

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_CONTEXT_FLAGS_H_
