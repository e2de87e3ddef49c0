// Copyright 2026 The DCS Authors.
#include "services/did_you_mean.h"

#include <algorithm>
#include <numeric>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "services/command_line.h"

namespace dcs::services {
namespace {

// The option `name` ("--addr", "-o") names in `command` or a command it is under (their flags
// may follow it), or null.
const CLI::Option* FindOption(const CLI::App& command, const std::string& name) {
  for (const CLI::App* app = &command; app != nullptr; app = app->get_parent()) {
    if (const CLI::Option* option = app->get_option_no_throw(name)) return option;
  }
  return nullptr;
}

const CLI::App* FindSubcommand(const CLI::App& command, const std::string& name) {
  const std::vector<const CLI::App*> found =
      command.get_subcommands([&name](const CLI::App* sub) { return sub->check_name(name); });
  return found.empty() ? nullptr : found.front();
}

// Whether a word after `command` is its argument rather than a subcommand.
bool TakesArguments(const CLI::App& command) {
  return !command.get_options([](const CLI::Option* option) { return !option->nonpositional(); })
              .empty();
}

std::string Suggestion(absl::string_view word, const std::vector<std::string>& candidates) {
  const std::optional<std::string> closest = ClosestName(word, candidates);
  return closest.has_value() ? absl::StrCat("; did you mean ", *closest, "?") : "";
}

}  // namespace

int EditDistance(absl::string_view a, absl::string_view b) {
  // Rows i-2, i-1 and i of the optimal string alignment distance.
  std::vector<int> before(b.size() + 1), previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), 0);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int replace = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, replace});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    before.swap(previous);
    previous.swap(current);
  }
  return previous[b.size()];
}

std::optional<std::string> ClosestName(absl::string_view word,
                                       const std::vector<std::string>& candidates) {
  std::optional<std::string> closest;
  int best = std::min<int>(2, (static_cast<int>(word.size()) - 1) / 2);
  for (const std::string& candidate : candidates) {
    const int distance = EditDistance(word, candidate);
    if (distance <= best && (!closest.has_value() || distance < EditDistance(word, *closest))) {
      closest = candidate;
      best = distance;
    }
  }
  return closest;
}

std::optional<std::string> UnknownNameError(const CLI::App& program,
                                            const std::vector<std::string>& args) {
  const CLI::App* command = &program;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") break;
    double number = 0;
    if (arg.size() > 1 && arg[0] == '-' && !absl::SimpleAtod(arg, &number)) {
      const bool is_long = absl::StartsWith(arg, "--");
      const std::string name = is_long ? arg.substr(0, arg.find('=')) : arg.substr(0, 2);
      const CLI::Option* option = FindOption(*command, name);
      if (option == nullptr) {
        std::vector<std::string> flags;
        for (const CLI::App* app = command; app != nullptr; app = app->get_parent()) {
          for (const CLI::Option* known : app->get_options()) {
            for (const std::string& long_name : known->get_lnames()) {
              flags.push_back("--" + long_name);
            }
          }
        }
        return absl::StrCat("unknown flag ", name, " for `", CommandPath(*command), "`",
                            is_long ? Suggestion(name, flags) : "");
      }
      // Its value is the next argument unless attached ("--addr=x", "-ojson").
      const bool attached = is_long ? arg.size() > name.size() : arg.size() > 2;
      if (option->get_expected_min() > 0 && !attached) ++i;
      continue;
    }
    if (const CLI::App* sub = FindSubcommand(*command, arg)) {
      command = sub;
      continue;
    }
    const std::vector<const CLI::App*> subcommands = command->get_subcommands({});
    if (subcommands.empty() || TakesArguments(*command)) continue;
    std::vector<std::string> names;
    for (const CLI::App* sub : subcommands) names.push_back(sub->get_name());
    return absl::StrCat("unknown command '", arg, "' for `", CommandPath(*command), "`",
                        Suggestion(arg, names));
  }
  return std::nullopt;
}

}  // namespace dcs::services
