// Copyright 2026 The DCS Authors.
#include "run/search_space_yaml.h"

#include <cmath>
#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "run/config_keys.h"

namespace dcs::run {
namespace {

const KeyTable<SearchSpace>& SpaceKeys() {
  static const KeyTable<SearchSpace>* const keys = new KeyTable<SearchSpace>({
      {.name = "parameters",
       .meaning = "the parameters, in the order a trial suggests them",
       .type = "list of parameters",
       .default_value = "required"},
  });
  return *keys;
}

const KeyTable<SearchParameter>& ParameterKeys() {
  static const KeyTable<SearchParameter>* const keys = [] {
    const FloatDistribution float_defaults;
    const IntDistribution int_defaults;
    return new KeyTable<SearchParameter>({
        {.name = "name",
         .meaning = "the parameter's name; in a study sweep, the run config's key path it sets",
         .type = "string",
         .default_value = "required"},
        {.name = "type",
         .meaning = "float and int: a value in [low, high]; categorical: one of the choices",
         .type = "one of {float, int, categorical}",
         .default_value = "required"},
        {.name = "low",
         .meaning = "the least value (an int's: an integer)",
         .type = "number",
         .default_value = "required (float, int)"},
        {.name = "high",
         .meaning = "the greatest value, at least low",
         .type = "number",
         .default_value = "required (float, int)"},
        {.name = "log",
         .meaning = "sampled uniformly in log space (low > 0; an int's low >= 1, step 1)",
         .type = "bool",
         .default_value = ValueText(float_defaults.log)},
        {.name = "step",
         .meaning = "values low, low + step, ..., high only (not with log)",
         .type = "number",
         .default_value = absl::StrCat("none (float), ", int_defaults.step, " (int)")},
        {.name = "choices",
         .meaning = "a categorical's names, each once",
         .type = "list of names",
         .default_value = "required (categorical)"},
        {.name = "when",
         .meaning = "{parent: choice or [choices]}: the parameter exists only when the earlier "
                    "categorical parent took one of them",
         .type = "mapping",
         .default_value = "none (always)"},
    });
  }();
  return *keys;
}

// Appends the words of the list `node` at `path` to `choices`.
absl::Status ReadChoices(YamlReader& reader, const YAML::Node& node, const std::string& path,
                         std::vector<std::string>& choices) {
  return reader.ForEachItem(
      node, path, "a list of choices", [&](const YAML::Node& item, const std::string& item_path) {
        DCS_ASSIGN_OR_RETURN(choices.emplace_back(), reader.Word(item, item_path));
        return absl::OkStatus();
      });
}

absl::StatusOr<SearchParameter> ReadParameter(YamlReader& reader, const YAML::Node& node,
                                              const std::string& path) {
  SearchParameter parameter;
  std::optional<std::string> type;
  std::optional<double> low;
  std::optional<double> high;
  std::optional<double> step;
  bool log = false;
  std::vector<std::string> choices;
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      node, path, ParameterKeys().names(),
      [&](const std::string& key, const YAML::Node& value, const std::string& key_path) {
        if (key == "name") {
          DCS_ASSIGN_OR_RETURN(parameter.name, reader.Word(value, key_path));
        } else if (key == "type") {
          DCS_ASSIGN_OR_RETURN(type, reader.Word(value, key_path));
        } else if (key == "low") {
          DCS_ASSIGN_OR_RETURN(low, reader.Number(value, key_path));
        } else if (key == "high") {
          DCS_ASSIGN_OR_RETURN(high, reader.Number(value, key_path));
        } else if (key == "step") {
          DCS_ASSIGN_OR_RETURN(step, reader.Number(value, key_path));
        } else if (key == "log") {
          DCS_ASSIGN_OR_RETURN(log, reader.Bool(value, key_path));
        } else if (key == "choices") {
          return ReadChoices(reader, value, key_path, choices);
        } else {  // when: {parent: choice or [choices]}
          ParameterCondition condition;
          DCS_RETURN_IF_ERROR(reader.ForEachEntry(
              value, key_path,
              [&](const std::string& parent, const YAML::Node& chosen,
                  const std::string& parent_path) {
                if (!condition.parent.empty()) {
                  return reader.Error(key_path, value, "a condition names one parent");
                }
                condition.parent = parent;
                if (chosen.IsSequence()) {
                  return ReadChoices(reader, chosen, parent_path, condition.choices);
                }
                DCS_ASSIGN_OR_RETURN(condition.choices.emplace_back(),
                                     reader.Word(chosen, parent_path));
                return absl::OkStatus();
              }));
          parameter.condition = std::move(condition);
        }
        return absl::OkStatus();
      }));
  if (parameter.name.empty()) return reader.Error(path, node, "a parameter needs a 'name'");
  if (!type.has_value()) {
    return reader.Error(path, node, "a parameter needs a 'type' (float, int or categorical)");
  }
  const bool numerical = *type == "float" || *type == "int";
  if (numerical && (!low.has_value() || !high.has_value())) {
    return reader.Error(path, node, absl::StrCat("a ", *type, " parameter needs 'low' and 'high'"));
  }
  if (numerical && !choices.empty()) {
    return reader.Error(path, node, "only a categorical parameter has 'choices'");
  }
  if (*type == "float") {
    parameter.distribution =
        FloatDistribution{.low = *low, .high = *high, .log = log, .step = step};
  } else if (*type == "int") {
    // An integer an int64_t holds: tested before casting, which is undefined out of its range.
    const auto whole = [](double x) {
      return x >= -0x1p63 && x < 0x1p63 && x == std::trunc(x);  // false for NaN too
    };
    if (!whole(*low) || !whole(*high) || (step.has_value() && !whole(*step))) {
      return reader.Error(path, node,
                          "an int parameter's low, high and step are integers that fit in 64 bits");
    }
    parameter.distribution = IntDistribution{.low = static_cast<int64_t>(*low),
                                             .high = static_cast<int64_t>(*high),
                                             .log = log,
                                             .step = static_cast<int64_t>(step.value_or(1))};
  } else if (*type == "categorical") {
    if (low.has_value() || high.has_value() || step.has_value() || log) {
      return reader.Error(path, node, "a categorical parameter has 'choices', not a range");
    }
    parameter.distribution = CategoricalDistribution{std::move(choices)};
  } else {
    return reader.Error(absl::StrCat(path, ".type"), node,
                        absl::StrCat("unknown type '", *type, "' (float, int or categorical)"));
  }
  return parameter;
}

}  // namespace

absl::StatusOr<SearchSpace> ReadSearchSpace(YamlReader& reader, const YAML::Node& node,
                                            absl::string_view path) {
  SearchSpace space;
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      node, path, SpaceKeys().names(),
      [&](const std::string&, const YAML::Node& value, const std::string& key_path) {
        return reader.ForEachItem(value, key_path, "a list of parameters",
                                  [&](const YAML::Node& item, const std::string& item_path) {
                                    DCS_ASSIGN_OR_RETURN(SearchParameter parameter,
                                                         ReadParameter(reader, item, item_path));
                                    space.parameters.push_back(std::move(parameter));
                                    return absl::OkStatus();
                                  });
      }));
  if (absl::Status status = ValidateSearchSpace(space); !status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(reader.where(), ": ", status.message()));
  }
  return space;
}

std::vector<KeySection> SearchSpaceReference() {
  return {{"", Describe(SpaceKeys())}, {"parameters[i]", Describe(ParameterKeys())}};
}

absl::StatusOr<SearchSpace> ParseSearchSpaceYaml(absl::string_view text, absl::string_view where) {
  YamlReader reader{std::string(where)};
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(text));
  return ReadSearchSpace(reader, root, "");
}

}  // namespace dcs::run
