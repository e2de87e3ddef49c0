// Copyright 2026 The DCS Authors.
#include "coordinator/schedule_yaml.h"

#include <cstdlib>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::coordinator {
namespace {

absl::Status Error(absl::string_view where, const YAML::Node& node, absl::string_view message) {
  return absl::InvalidArgumentError(
      absl::StrCat(where, ": line ", node.Mark().line + 1, ": ", message));
}

// A YAML scalar as a number, if it is one ("0.25", "-3", "1e-3").
std::optional<double> AsNumber(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return value;
}

absl::StatusOr<env::ScheduleParam> ParamFromYaml(const YAML::Node& node, const std::string& key,
                                                 absl::string_view where) {
  if (node.IsScalar()) {
    if (std::optional<double> number = AsNumber(node)) return *number;
    return node.Scalar();
  }
  if (node.IsSequence()) {
    std::vector<double> values;
    for (const YAML::Node& item : node) {
      std::optional<double> number = item.IsScalar() ? AsNumber(item) : std::nullopt;
      if (!number.has_value()) {
        return Error(where, item, absl::StrCat("'", key, "' must be a list of numbers"));
      }
      values.push_back(*number);
    }
    return values;
  }
  return Error(where, node, absl::StrCat("'", key, "' must be a number, a word or a list"));
}

}  // namespace

absl::StatusOr<env::ScheduleConfig> ScheduleConfigFromYaml(const YAML::Node& node,
                                                           absl::string_view where) {
  if (!node.IsMap()) return Error(where, node, "a schedule must be a mapping with a family");
  env::ScheduleConfig config;
  for (const auto& entry : node) {
    const std::string key = entry.first.as<std::string>();
    const YAML::Node& value = entry.second;
    if (key == "family") {
      if (!value.IsScalar()) return Error(where, value, "'family' must be a name");
      config.family = value.Scalar();
    } else if (key == "parts") {
      if (!value.IsSequence()) return Error(where, value, "'parts' must be a list of schedules");
      for (const YAML::Node& part : value) {
        DCS_ASSIGN_OR_RETURN(env::ScheduleConfig part_config,
                             ScheduleConfigFromYaml(part, where));
        config.parts.push_back(std::move(part_config));
      }
    } else {
      DCS_ASSIGN_OR_RETURN(config.params[key], ParamFromYaml(value, key, where));
    }
  }
  if (config.family.empty()) return Error(where, node, "a schedule needs a 'family'");
  return config;
}

absl::StatusOr<std::vector<env::ScheduleConfig>> ParseScheduleConfigsYaml(
    absl::string_view text, absl::string_view where) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": line ", e.mark.line + 1, ": ", e.msg));
  }
  std::vector<env::ScheduleConfig> configs;
  if (root.IsSequence()) {
    for (const YAML::Node& item : root) {
      DCS_ASSIGN_OR_RETURN(env::ScheduleConfig config, ScheduleConfigFromYaml(item, where));
      configs.push_back(std::move(config));
    }
  } else {
    DCS_ASSIGN_OR_RETURN(env::ScheduleConfig config, ScheduleConfigFromYaml(root, where));
    configs.push_back(std::move(config));
  }
  if (configs.empty()) return absl::InvalidArgumentError(absl::StrCat(where, ": no schedule"));
  return configs;
}

}  // namespace dcs::coordinator
