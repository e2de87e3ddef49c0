// Copyright 2026 The DCS Authors.
#include "services/command_line.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/match.h"
#include "absl/strings/str_replace.h"
#include "services/did_you_mean.h"
#include "services/exit_codes.h"

namespace dcs::services {
namespace {

// The value of --config on the command line, if any ("--config F" or "--config=F").
std::optional<std::string> FindConfigPath(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const absl::string_view arg = argv[i];
    if (arg == "--") break;
    if (arg == "--config" && i + 1 < argc) return argv[i + 1];
    if (absl::StartsWith(arg, "--config=")) return std::string(arg.substr(9));
  }
  return std::nullopt;
}

// The options that argv sets, by any of their names ("--listen=x", "--listen x", "-o json").
absl::flat_hash_set<const CLI::Option*> OptionsOnCommandLine(const CLI::App& app, int argc,
                                                             const char* const* argv) {
  absl::flat_hash_set<const CLI::Option*> options;
  for (int i = 1; i < argc; ++i) {
    const absl::string_view arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 2 || arg[0] != '-') continue;
    const absl::string_view name =
        absl::StartsWith(arg, "--") ? arg.substr(0, arg.find('=')) : arg.substr(0, 2);
    if (const CLI::Option* option = app.get_option_no_throw(std::string(name))) {
      options.insert(option);
    }
  }
  return options;
}

// The config file's entries as "--key=value" arguments, checked against `app`'s options,
// leaving out those the command line sets: the command line wins.
absl::StatusOr<std::vector<std::string>> ConfigArguments(
    const CLI::App& app, const std::string& path,
    const absl::flat_hash_set<const CLI::Option*>& on_command_line) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    return absl::NotFoundError(absl::StrCat("config file ", path, ": cannot be read"));
  } catch (const YAML::Exception& e) {
    return absl::InvalidArgumentError(
        absl::StrCat("config file ", path, ": line ", e.mark.line + 1, ", column ",
                     e.mark.column + 1, ": ", e.msg));
  }
  if (root.IsNull()) return std::vector<std::string>{};
  if (!root.IsMap()) {
    return absl::InvalidArgumentError(
        absl::StrCat("config file ", path, ": expected a mapping of flag names to values"));
  }
  std::vector<std::string> arguments;
  for (const auto& entry : root) {
    const std::string key = absl::StrReplaceAll(entry.first.as<std::string>(), {{"_", "-"}});
    const std::string flag = absl::StrCat("--", key);
    const CLI::Option* option = app.get_option_no_throw(flag);
    if (key == "config" || option == nullptr) {
      return absl::InvalidArgumentError(
          absl::StrCat("config file ", path, ": unknown key '", entry.first.as<std::string>(),
                       "' (keys are the program's long flags; see --help)"));
    }
    if (on_command_line.contains(option)) continue;
    const YAML::Node& value = entry.second;
    std::vector<YAML::Node> values;
    if (value.IsSequence()) {
      for (const YAML::Node& item : value) values.push_back(item);
    } else {
      values.push_back(value);
    }
    for (const YAML::Node& item : values) {
      if (!item.IsScalar()) {
        return absl::InvalidArgumentError(absl::StrCat(
            "config file ", path, ": line ", item.Mark().line + 1, ": '", key,
            "' must be a value or a list of values"));
      }
      arguments.push_back(absl::StrCat(flag, "=", item.Scalar()));
    }
  }
  return arguments;
}

}  // namespace

CLI::Option* AddDurationOption(CLI::App& app, const std::string& name, absl::Duration* value,
                               const std::string& description) {
  return app
      .add_option_function<std::string>(
          name,
          [name, value](const std::string& text) {
            absl::Duration parsed;
            if (!absl::ParseDuration(text, &parsed) || parsed < absl::ZeroDuration()) {
              throw CLI::ValidationError(
                  name, absl::StrCat("'", text, "' is not a duration such as 500ms, 5s or 2m"));
            }
            *value = parsed;
          },
          description)
      ->type_name("DURATION")
      ->default_str(absl::FormatDuration(*value));
}

std::string CommandPath(const CLI::App& command) {
  const CLI::App* parent = command.get_parent();
  return parent == nullptr ? command.get_name()
                           : absl::StrCat(CommandPath(*parent), " ", command.get_name());
}

void PrintError(absl::string_view program, absl::string_view message) {
  std::cerr << program << ": error: " << message << std::endl;
}

std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv) {
  std::vector<std::string> arguments;
  if (app.get_option_no_throw("--config") != nullptr) {
    if (std::optional<std::string> path = FindConfigPath(argc, argv)) {
      absl::StatusOr<std::vector<std::string>> from_file =
          ConfigArguments(app, *path, OptionsOnCommandLine(app, argc, argv));
      if (!from_file.ok()) {
        PrintError(app.get_name(), from_file.status().message());
        return kExitConfig;
      }
      arguments = *std::move(from_file);
    }
  }
  arguments.insert(arguments.end(), argv + 1, argv + argc);
  std::reverse(arguments.begin(), arguments.end());  // CLI11 consumes from the back
  try {
    app.parse(arguments);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 names an unknown flag or command only as an extra argument, and suggests nothing.
    const std::optional<std::string> unknown =
        UnknownNameError(app, std::vector<std::string>(argv + 1, argv + argc));
    PrintError(app.get_name(), absl::StrCat(unknown.value_or(e.what()), " (see --help)"));
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace dcs::services
