// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SEARCH_SPACE_H_
#define DCS_RUN_SEARCH_SPACE_H_

// A search space for a study (Optuna's distributions): float, int and categorical parameters, some
// of them conditional on an earlier categorical's choice (a multi-stage schedule's stage k has a
// mode, and a sinusoid's period exists only in the stages whose mode is sinusoidal).
//
// Values are kept in Optuna's internal representation, a double per parameter: a float or int
// parameter's value in its own scale (not the log scale), a categorical's choice index. A trial's
// values hold exactly its active parameters. Plain data; the functions are thread-safe.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "absl/status/status.h"

namespace dcs::run {

// Uniform on [low, high]; log-uniform with `log` (low > 0); on the grid low + k·step with `step`
// (not with `log`; high - low a multiple of step).
struct FloatDistribution {
  double low = 0.0;
  double high = 0.0;
  bool log = false;
  std::optional<double> step;
};

// Integers low, low + step, ..., high; log-uniform over [low, high] with `log` (low >= 1, step 1).
struct IntDistribution {
  int64_t low = 0;
  int64_t high = 0;
  bool log = false;
  int64_t step = 1;
};

// One of `choices` (names, at least one, each once).
struct CategoricalDistribution {
  std::vector<std::string> choices;
};

using Distribution = std::variant<FloatDistribution, IntDistribution, CategoricalDistribution>;

// The parameter exists only when the categorical parameter `parent` (earlier in the space) is
// active and took one of `choices`.
struct ParameterCondition {
  std::string parent;
  std::vector<std::string> choices;
};

struct SearchParameter {
  std::string name;
  Distribution distribution;
  std::optional<ParameterCondition> condition;
};

// The parameters in the order a trial suggests them.
struct SearchSpace {
  std::vector<SearchParameter> parameters;
};

// Parameter name -> value, internal representation.
using ParameterValues = std::map<std::string, double>;

// INVALID_ARGUMENT naming the parameter and the problem: an empty space, a repeated or empty name,
// low > high, a non-finite bound, log with low <= 0 (float) or low < 1 or a step (int), a step that
// is not positive or does not divide high - low, no or repeated choices, a condition whose parent
// is not an earlier categorical or whose choice is not one of the parent's.
absl::Status ValidateSearchSpace(const SearchSpace& space);

// The parameter called `name`, or null if the space has none.
const SearchParameter* FindParameter(const SearchSpace& space, const std::string& name);

// Whether `parameter` exists in a trial whose earlier parameters took `values`.
bool IsActive(const SearchParameter& parameter, const SearchSpace& space,
              const ParameterValues& values);

// Whether `value` (internal representation) is one `distribution` can take: in range, on the grid,
// an integer where it must be.
bool Contains(const Distribution& distribution, double value);

// The choice a categorical's value (its index) stands for. REQUIRES: Contains(choices, value).
const std::string& ChoiceOf(const CategoricalDistribution& choices, double value);

// Whether the distribution has a single value (nothing to sample).
bool IsSingleValued(const Distribution& distribution);

}  // namespace dcs::run

#endif  // DCS_RUN_SEARCH_SPACE_H_
