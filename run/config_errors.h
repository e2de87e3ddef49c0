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
#include <set>
#include <string>
#include <utility>
#include <vector>

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

  // The file errors name; empty for a config built in code.
  const std::string& where() const { return where_; }

 private:
  std::string where_;
  const std::map<std::string, int>* lines_ = nullptr;
  const PathMap* shown_path_ = nullptr;
};

// The problems of one config, collected so that they are reported together rather than one at
// a time: each check adds what it finds and goes on. Each problem is kept once (a sweep spec
// finds the same problem of its base in every trial), in the order found.
class ConfigProblems {
 public:
  // Adds `status` unless it is OK or a problem with the same message is already kept.
  void Add(const absl::Status& status);

  bool empty() const { return problems_.empty(); }
  // Problems added, repetitions included: a check compares it before and after to learn
  // whether it found anything.
  int reported() const { return reported_; }
  // Each problem once, in the order found.
  const std::vector<absl::Status>& problems() const { return problems_; }

  // OK if there are none; the problem itself if there is one; otherwise INVALID_ARGUMENT
  // "N problems in <where>:" (or "N problems:" without `where`) with each on its own line.
  absl::Status ToStatus(absl::string_view where) const;

 private:
  std::vector<absl::Status> problems_;
  std::set<std::string, std::less<>> seen_;
  int reported_ = 0;
};

// "<path>[<index>]".
std::string ItemPath(absl::string_view path, size_t index);
// "<path>.<key>", or `key` at the top level (empty `path`).
std::string KeyPath(absl::string_view path, absl::string_view key);

}  // namespace dcs::run

#endif  // DCS_RUN_CONFIG_ERRORS_H_
