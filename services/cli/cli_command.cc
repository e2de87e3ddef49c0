// Copyright 2026 The DCS Authors.
#include "services/cli/cli_command.h"

#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

#include "services/command_line.h"
#include "services/exit_codes.h"

namespace dcs::services::cli {

namespace {

std::string& UnavailableHint() {
  static std::string* const hint = new std::string();  // never destroyed: read until exit
  return *hint;
}

// `text` as a finite number, or nullopt.
std::optional<double> FiniteNumber(absl::string_view text) {
  double value = 0;
  if (!absl::SimpleAtod(text, &value) || !std::isfinite(value)) return std::nullopt;
  return value;
}

}  // namespace

void SetUnavailableHint(std::string hint) { UnavailableHint() = std::move(hint); }

int FailCommand(const absl::Status& status) {
  // Without payloads: they are for code (common/status_util.h's field), not for the reader.
  std::string line = status.ToString(absl::StatusToStringMode::kWithNoExtraData);
  if (absl::IsUnavailable(status) && !UnavailableHint().empty()) {
    absl::StrAppend(&line, "; ", UnavailableHint());
  }
  PrintError("dcs", line);
  return ExitCodeFor(status);
}

absl::StatusOr<std::vector<double>> ParseNumberList(absl::string_view text,
                                                    absl::string_view flag) {
  std::vector<double> numbers;
  for (absl::string_view item : absl::StrSplit(text, ',')) {
    const std::optional<double> value = FiniteNumber(item);
    if (!value.has_value()) {
      return UsageError(
          absl::StrCat(flag, ": '", item, "' is not a finite number (expected a,b,c,...)"));
    }
    numbers.push_back(*value);
  }
  return numbers;
}

CLI::Option* AddOutDirectory(CLI::App& command, std::string* out, std::string help) {
  return command.add_option("--out", *out, std::move(help))->type_name("DIR");
}

CLI::Option* AddOutFile(CLI::App& command, std::string* out, std::string help) {
  return command.add_option("--out", *out, std::move(help))->type_name("FILE");
}

absl::StatusOr<std::map<std::string, double>> ParseAssignments(
    const std::vector<std::string>& assignments, absl::string_view flag) {
  std::map<std::string, double> values;
  for (const std::string& assignment : assignments) {
    const std::vector<std::string> parts = absl::StrSplit(assignment, absl::MaxSplits('=', 1));
    const std::optional<double> value =
        parts.size() == 2 ? FiniteNumber(parts[1]) : std::nullopt;
    if (!value.has_value()) {
      return UsageError(absl::StrCat(flag, ": expected name=value with a finite number, got '",
                                     assignment, "'"));
    }
    if (!values.emplace(parts[0], *value).second) {
      return UsageError(absl::StrCat(flag, ": '", parts[0], "' is given twice"));
    }
  }
  return values;
}

}  // namespace dcs::services::cli
