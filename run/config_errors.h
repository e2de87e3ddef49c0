// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_CONFIG_ERRORS_H_
#define DCS_RUN_CONFIG_ERRORS_H_

// How every config error reads: "<where>: <path>: line <n>: <message>", with the YAML path of
// the field (`stages[1].schedule.period`). Validators write errors through a ConfigErrors, so
// a config read from a file (run/yaml_reader.h) gets its file name and lines, and one built
// in code gets the path alone. Thread-safe (const); borrows the lines it is given.

#include <cstddef>
#include <map>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace dcs::run {

class ConfigErrors {
 public:
  // Errors with the path alone.
  ConfigErrors() = default;
  // Errors naming `where` (a file) and, for paths in `lines`, their line. Borrows `lines`.
  ConfigErrors(std::string where, const std::map<std::string, int>* lines)
      : where_(std::move(where)), lines_(lines) {}

  // INVALID_ARGUMENT "<where>: <path>: line <n>: <message>", leaving out what is unknown.
  absl::Status At(absl::string_view path, absl::string_view message) const;

 private:
  std::string where_;
  const std::map<std::string, int>* lines_ = nullptr;
};

// "<path>[<index>]".
std::string ItemPath(absl::string_view path, size_t index);
// "<path>.<key>", or `key` at the top level (empty `path`).
std::string KeyPath(absl::string_view path, absl::string_view key);

}  // namespace dcs::run

#endif  // DCS_RUN_CONFIG_ERRORS_H_
