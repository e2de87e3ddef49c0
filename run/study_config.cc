// Copyright 2026 The DCS Authors.
#include "run/study_config.h"

#include <optional>
#include <variant>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/status_macros.h"
#include "run/run_spec_yaml.h"
#include "run/yaml_reader.h"
#include "run/yaml_splice.h"

namespace dcs::run {
namespace {

// A value as the run config's YAML spells it: a categorical's choice as a plain scalar (so a
// choice written as a number is one), an int in digits, a float with 17 significant digits.
std::string ValueText(const SearchParameter& parameter, double value) {
  if (const auto* choices = std::get_if<CategoricalDistribution>(&parameter.distribution)) {
    return ChoiceOf(*choices, value);
  }
  if (std::holds_alternative<IntDistribution>(parameter.distribution)) {
    return absl::StrCat(static_cast<int64_t>(value));
  }
  return absl::StrFormat("%.17g", value);
}

}  // namespace

absl::Status ValidateStudyKeyPaths(const SearchSpace& space) {
  std::vector<std::vector<KeyPathStep>> paths;
  for (const SearchParameter& parameter : space.parameters) {
    std::optional<std::vector<KeyPathStep>> steps = ParseKeyPath(parameter.name);
    if (!steps.has_value()) {
      return absl::InvalidArgumentError(
          absl::StrCat("parameter '", parameter.name,
                       "': its name is not a run config's key path (names joined by '.', with "
                       "[i] for a list's item, as stages[1].schedule.period)"));
    }
    for (size_t i = 0; i < paths.size(); ++i) {
      if (KeyPathsOverlap(paths[i], *steps)) {
        return absl::InvalidArgumentError(absl::StrCat("parameters '", space.parameters[i].name,
                                                       "' and '", parameter.name,
                                                       "' write to overlapping key paths"));
      }
    }
    paths.push_back(*std::move(steps));
  }
  return absl::OkStatus();
}

absl::StatusOr<SeededRuns> TrialRunConfig(absl::string_view base, absl::string_view where,
                                          const SearchSpace& space,
                                          const ParameterValues& values) {
  DCS_RETURN_IF_ERROR(ValidateStudyKeyPaths(space));
  YamlReader reader{std::string(where)};
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(base));
  YamlArena arena(root);
  // Held by construction, never assigned: assigning a YAML::Node rewrites the node it refers to.
  std::optional<YAML::Node> config;
  config.emplace(root);
  size_t written = 0;
  for (const SearchParameter& parameter : space.parameters) {
    const auto value = values.find(parameter.name);
    if (value == values.end()) continue;
    if (!Contains(parameter.distribution, value->second)) {
      return absl::InvalidArgumentError(
          absl::StrCat("parameter '", parameter.name, "' cannot take the value ", value->second));
    }
    // Loaded rather than constructed: yaml-cpp marks a constructed string as quoted, and a
    // quoted number is a string to the run config's reader.
    const std::string text = ValueText(parameter, value->second);
    const absl::StatusOr<YAML::Node> scalar =
        YamlReader(absl::StrCat("parameter '", parameter.name, "'")).Load(text);
    if (!scalar.ok() || !scalar->IsScalar()) {
      return absl::InvalidArgumentError(absl::StrCat("parameter '", parameter.name, "': '", text,
                                                     "' is not a plain YAML scalar"));
    }
    absl::StatusOr<YAML::Node> with =
        WithValueAt(arena, *config, *ParseKeyPath(parameter.name), *scalar);
    if (!with.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat(where, ": parameter '", parameter.name, "': ", with.status().message()));
    }
    config.emplace(*with);
    ++written;
  }
  if (written != values.size()) {
    return absl::InvalidArgumentError("the trial has values of parameters the space lacks");
  }
  std::string text = YamlText(*config);
  DCS_ASSIGN_OR_RETURN(RunSpec spec, ParseRunSpecYaml(text, where));
  return SeededRuns(std::move(spec), std::move(text));
}

}  // namespace dcs::run
