// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COMMAND_LINE_H_
#define DCS_SERVICES_COMMAND_LINE_H_

// Command-line parsing for every DCS program (CLI11), with an optional YAML config file for
// programs that define a --config option:
//
//   # coordinator.yaml: keys are long flag names; '_' and '-' are alike
//   listen: 0.0.0.0:50051
//   worker_timeout: 10s
//
// The command line wins over the file. Errors are printed as one line on stderr:
//   dcs-coordinator: error: config file c.yaml: unknown key 'lissten'
// Thread-compatible.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "common/enum_names.h"

namespace dcs::services {

// Parses argv into `app`. Returns std::nullopt when the program should go on, else the exit
// code to exit with now: kExitOk after --help (printed on stdout), kExitUsage after a bad flag,
// kExitConfig after an unreadable or malformed config file.
std::optional<int> ParseCommandLine(CLI::App& app, int argc, const char* const* argv);

// Adds a duration flag ("500ms", "5s", "2m") bound to `value`; negative durations are refused.
CLI::Option* AddDurationOption(CLI::App& app, const std::string& name, absl::Duration* value,
                               const std::string& description);

// Adds a flag that takes one of a fixed set of words, each naming a value of T ("json" ->
// LogFormat::kJson), bound to `value`. Another word is a usage error listing the allowed ones.
// `name` is CLI11's ("-o,--output").
template <typename T>
CLI::Option* AddChoiceOption(CLI::App& app, const std::string& name, T* value,
                             const std::vector<std::pair<std::string, T>>& choices,
                             const std::string& description);

// The choices of an enumeration's name table (common/enum_names.h), for AddChoiceOption.
template <typename E, size_t N>
std::vector<std::pair<std::string, E>> ChoicesOf(const EnumName<E> (&table)[N]) {
  std::vector<std::pair<std::string, E>> choices;
  for (const EnumName<E>& entry : table) choices.emplace_back(std::string(entry.name), entry.value);
  return choices;
}

// "dcs runs cancel": a command's names, from the program's on.
std::string CommandPath(const CLI::App& command);

// Prints "<program>: error: <message>" as one line on stderr.
void PrintError(absl::string_view program, absl::string_view message);

// Implementation details.

template <typename T>
CLI::Option* AddChoiceOption(CLI::App& app, const std::string& name, T* value,
                             const std::vector<std::pair<std::string, T>>& choices,
                             const std::string& description) {
  std::vector<std::string> words;
  std::string default_word;
  for (const auto& [word, choice] : choices) {
    words.push_back(word);
    if (choice == *value) default_word = word;
  }
  const std::string flag = name.substr(name.rfind(',') + 1);
  return app
      .add_option_function<std::string>(
          name,
          [flag, value, choices, allowed = absl::StrJoin(words, ", ")](const std::string& text) {
            for (const auto& [word, choice] : choices) {
              if (word == text) {
                *value = choice;
                return;
              }
            }
            throw CLI::ValidationError(flag, absl::StrCat("'", text, "' is not one of ", allowed));
          },
          description)
      ->type_name(absl::StrCat("{", absl::StrJoin(words, ","), "}"))
      ->default_str(default_word);
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_COMMAND_LINE_H_
