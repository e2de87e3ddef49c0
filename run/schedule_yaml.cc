// Copyright 2026 The DCS Authors.
#include "run/schedule_yaml.h"

#include <string>
#include <utility>
#include <variant>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "common/status_util.h"

namespace dcs::run {
namespace {

absl::StatusOr<env::ScheduleParam> ReadParam(YamlReader& reader, const YAML::Node& node,
                                             const std::string& path) {
  if (node.IsSequence()) {
    DCS_ASSIGN_OR_RETURN(std::vector<double> values, reader.Numbers(node, path));
    return values;
  }
  if (!node.IsScalar()) {
    return reader.Error(path, node, "must be a number, a word or a list of numbers");
  }
  DCS_ASSIGN_OR_RETURN(auto value, reader.NumberOrWord(node, path));
  return std::visit([](auto&& v) -> env::ScheduleParam { return std::move(v); }, std::move(value));
}

}  // namespace

absl::StatusOr<env::ScheduleConfig> ReadScheduleConfig(YamlReader& reader, const YAML::Node& node,
                                                       absl::string_view path) {
  env::ScheduleConfig config;
  bool has_family = false;
  DCS_RETURN_IF_ERROR(reader.ForEachEntry(
      node, path,
      [&](const std::string& key, const YAML::Node& value, const std::string& key_path) {
        if (key == "family") {
          has_family = true;
          DCS_ASSIGN_OR_RETURN(config.family, reader.Word(value, key_path));
        } else if (key == "parts") {
          return reader.ForEachItem(
              value, key_path, "a list of schedules",
              [&](const YAML::Node& part, const std::string& part_path) {
                DCS_ASSIGN_OR_RETURN(env::ScheduleConfig part_config,
                                     ReadScheduleConfig(reader, part, part_path));
                config.parts.push_back(std::move(part_config));
                return absl::OkStatus();
              });
        } else {
          DCS_ASSIGN_OR_RETURN(config.params[key], ReadParam(reader, value, key_path));
        }
        return absl::OkStatus();
      }));
  if (!has_family) {
    return reader.Error(path, node, "a schedule needs a 'family' (e.g. {family: constant})");
  }
  return config;
}

absl::StatusOr<std::vector<env::ScheduleConfig>> ParseScheduleConfigsYaml(
    absl::string_view text, absl::string_view where) {
  YamlReader reader{std::string(where)};
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(text));
  std::vector<env::ScheduleConfig> configs;
  if (root.IsSequence()) {
    DCS_RETURN_IF_ERROR(reader.ForEachItem(
        root, "", "a list of schedules", [&](const YAML::Node& item, const std::string& path) {
          DCS_ASSIGN_OR_RETURN(env::ScheduleConfig config, ReadScheduleConfig(reader, item, path));
          configs.push_back(std::move(config));
          return absl::OkStatus();
        }));
  } else {
    DCS_ASSIGN_OR_RETURN(env::ScheduleConfig config, ReadScheduleConfig(reader, root, ""));
    configs.push_back(std::move(config));
  }
  if (configs.empty()) return absl::InvalidArgumentError(absl::StrCat(where, ": no schedule"));
  return configs;
}

absl::Status ScheduleError(const ConfigErrors& errors, absl::string_view path,
                           const absl::Status& status) {
  const std::optional<std::string> field = ErrorField(status);
  return errors.At(field.has_value() ? KeyPath(path, *field) : std::string(path),
                   status.message());
}

}  // namespace dcs::run
