// Copyright 2026 The DCS Authors.
#include "run/search_space.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

namespace dcs::run {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Deduced without this guide since C++20 (aggregate deduction), but not yet by clang 14.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// Whether `steps` (a count of grid steps, as computed) is within rounding of an integer.
bool IsWhole(double steps) { return std::abs(steps - std::round(steps)) <= 1e-8 * (1 + steps); }

absl::Status CheckDistribution(const FloatDistribution& d) {
  if (!std::isfinite(d.low) || !std::isfinite(d.high))
    return absl::InvalidArgumentError("bounds must be finite");
  if (d.low > d.high)
    return absl::InvalidArgumentError(absl::StrCat("low ", d.low, " is above high ", d.high));
  if (d.log && d.low <= 0)
    return absl::InvalidArgumentError(absl::StrCat("a log range needs low > 0, got ", d.low));
  if (d.step.has_value()) {
    if (d.log) return absl::InvalidArgumentError("a float cannot have both log and step");
    if (!(*d.step > 0) || !std::isfinite(*d.step))
      return absl::InvalidArgumentError(absl::StrCat("step must be positive, got ", *d.step));
    if (!IsWhole((d.high - d.low) / *d.step)) {
      return absl::InvalidArgumentError(
          absl::StrCat("step ", *d.step, " does not divide high - low = ", d.high - d.low));
    }
  }
  return absl::OkStatus();
}

absl::Status CheckDistribution(const IntDistribution& d) {
  if (d.low > d.high)
    return absl::InvalidArgumentError(absl::StrCat("low ", d.low, " is above high ", d.high));
  if (d.step < 1)
    return absl::InvalidArgumentError(absl::StrCat("step must be at least 1, got ", d.step));
  if (d.log && d.low < 1)
    return absl::InvalidArgumentError(absl::StrCat("a log range needs low >= 1, got ", d.low));
  if (d.log && d.step != 1) return absl::InvalidArgumentError("a log int range must have step 1");
  if ((d.high - d.low) % d.step != 0) {
    return absl::InvalidArgumentError(
        absl::StrCat("step ", d.step, " does not divide high - low = ", d.high - d.low));
  }
  return absl::OkStatus();
}

absl::Status CheckDistribution(const CategoricalDistribution& d) {
  if (d.choices.empty()) return absl::InvalidArgumentError("no choices");
  std::set<std::string> seen;
  for (const std::string& choice : d.choices) {
    if (!seen.insert(choice).second)
      return absl::InvalidArgumentError(absl::StrCat("choice '", choice, "' is given twice"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::Status ValidateSearchSpace(const SearchSpace& space) {
  if (space.parameters.empty())
    return absl::InvalidArgumentError("the search space has no parameters");
  std::set<std::string> earlier;
  for (const SearchParameter& parameter : space.parameters) {
    const auto fail = [&](absl::string_view problem) {
      return absl::InvalidArgumentError(
          absl::StrCat("parameter '", parameter.name, "': ", problem));
    };
    if (parameter.name.empty()) return absl::InvalidArgumentError("a parameter has no name");
    if (earlier.contains(parameter.name)) return fail("the name is given twice");
    if (absl::Status status =
            std::visit([](const auto& d) { return CheckDistribution(d); }, parameter.distribution);
        !status.ok()) {
      return fail(status.message());
    }
    if (parameter.condition.has_value()) {
      const ParameterCondition& condition = *parameter.condition;
      const SearchParameter* parent =
          earlier.contains(condition.parent) ? FindParameter(space, condition.parent) : nullptr;
      const auto* choices =
          parent == nullptr ? nullptr : std::get_if<CategoricalDistribution>(&parent->distribution);
      if (choices == nullptr) {
        return fail(absl::StrCat("its condition's parent '", condition.parent,
                                 "' is not a categorical parameter before it"));
      }
      if (condition.choices.empty()) return fail("its condition names no choice");
      for (const std::string& choice : condition.choices) {
        if (std::find(choices->choices.begin(), choices->choices.end(), choice) ==
            choices->choices.end()) {
          return fail(absl::StrCat("its condition's choice '", choice, "' is not one of '",
                                   condition.parent, "' (", absl::StrJoin(choices->choices, ", "),
                                   ")"));
        }
      }
    }
    earlier.insert(parameter.name);
  }
  return absl::OkStatus();
}

const SearchParameter* FindParameter(const SearchSpace& space, const std::string& name) {
  for (const SearchParameter& parameter : space.parameters) {
    if (parameter.name == name) return &parameter;
  }
  return nullptr;
}

bool IsActive(const SearchParameter& parameter, const SearchSpace& space,
              const ParameterValues& values) {
  if (!parameter.condition.has_value()) return true;
  const ParameterCondition& condition = *parameter.condition;
  const auto value = values.find(condition.parent);
  const SearchParameter* parent = FindParameter(space, condition.parent);
  if (value == values.end() || parent == nullptr) return false;
  const auto& choices = std::get<CategoricalDistribution>(parent->distribution).choices;
  const auto index = static_cast<size_t>(value->second);
  return index < choices.size() && std::find(condition.choices.begin(), condition.choices.end(),
                                             choices[index]) != condition.choices.end();
}

bool Contains(const Distribution& distribution, double value) {
  if (!std::isfinite(value)) return false;
  return std::visit(Overloaded{[value](const FloatDistribution& d) {
                                 return d.low <= value && value <= d.high &&
                                        (!d.step.has_value() || IsWhole((value - d.low) / *d.step));
                               },
                               [value](const IntDistribution& d) {
                                 if (value != std::round(value) ||
                                     value < static_cast<double>(d.low) ||
                                     value > static_cast<double>(d.high)) {
                                   return false;
                                 }
                                 return (static_cast<int64_t>(value) - d.low) % d.step == 0;
                               },
                               [value](const CategoricalDistribution& d) {
                                 return value == std::round(value) && value >= 0 &&
                                        value < static_cast<double>(d.choices.size());
                               }},
                    distribution);
}

const std::string& ChoiceOf(const CategoricalDistribution& choices, double value) {
  return choices.choices[static_cast<size_t>(value)];
}

bool IsSingleValued(const Distribution& distribution) {
  return std::visit(
      Overloaded{[](const FloatDistribution& d) { return d.low == d.high; },
                 [](const IntDistribution& d) { return d.low == d.high; },
                 [](const CategoricalDistribution& d) { return d.choices.size() == 1; }},
      distribution);
}

}  // namespace dcs::run
