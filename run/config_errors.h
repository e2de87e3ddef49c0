// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_CONFIG_ERRORS_H_
#define DCS_RUN_CONFIG_ERRORS_H_

// How every config error reads: "<where>: <path>: line <n>: <message>", with the YAML path of
// the field (`stages[1].schedule.period`). Validators write errors through a ConfigErrors, so
// a config read from a file (run/yaml_reader.h) gets its file name and lines, and one built
// in code gets the path alone. Thread-safe (const); borrows the lines and path map it is given.

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace dcs::run {

// The path an error shows for the field at `path` of the config read. A sweep spec assembles
// each trial's run config from several places of the spec, and shows each field where the spec
// wrote it (`ppo.gamma` of a trial is `conditions[2].ppo.gamma`: run/sweep_spec_yaml.h). Without
// one, errors show paths as they are.
using PathMap = std::function<std::string(absl::string_view path)>;

class ConfigErrors {
 public:
  // Errors with the path alone.
  ConfigErrors() = default;
  // Errors naming `where` (a file) and, for paths in `lines`, their line; paths shown through
  // `shown_path` if it is given and not empty. Borrows `lines` and `shown_path`.
  ConfigErrors(std::string where, const std::map<std::string, int>* lines,
               const PathMap* shown_path = nullptr)
      : where_(std::move(where)), lines_(lines), shown_path_(shown_path) {}

  // INVALID_ARGUMENT "<where>: <path>: line <n>: <message>", leaving out what is unknown. The
  // line is the one noted for `path`; the path shown is `shown_path`'s.
  absl::Status At(absl::string_view path, absl::string_view message) const;

 private:
  std::string where_;
  const std::map<std::string, int>* lines_ = nullptr;
  const PathMap* shown_path_ = nullptr;
};

// "<path>[<index>]".
std::string ItemPath(absl::string_view path, size_t index);
// "<path>.<key>", or `key` at the top level (empty `path`).
std::string KeyPath(absl::string_view path, absl::string_view key);

}  // namespace dcs::run

#endif  // DCS_RUN_CONFIG_ERRORS_H_
