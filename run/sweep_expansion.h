// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SWEEP_EXPANSION_H_
#define DCS_RUN_SWEEP_EXPANSION_H_

// A sweep spec's conditions, as run/sweep_spec_yaml.cc reads them, expanded into trials: each
// combination of a condition's grid values named, and its run config in each mode spliced from
// the spec's nodes (run/yaml_splice.h) and validated as a run config is, each error shown at the
// path and line where the spec wrote the field. Internal to run/sweep_spec_yaml.cc; the format
// is documented in run/sweep_spec_yaml.h. Thread-compatible.

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "env/observe_mode.h"
#include "run/sweep_spec.h"
#include "run/yaml_reader.h"
#include "run/yaml_splice.h"

namespace dcs::run::internal {

// An observation mode as the spec gives it.
struct SpecMode {
  env::ObserveMode mode = env::ObserveMode::kNone;
  YAML::Node node;   // the trial's config takes it, line and all
  std::string path;  // where the spec gave it: `observe[1]`, `conditions[2].observe`
};

// One key of a condition's grid.
struct SpecGridKey {
  std::string key;                 // as written: "schedule.amplitude_frac"
  std::vector<KeyPathStep> steps;  // of `key`
  std::string path;                // in the spec: "conditions[1].grid.schedule.amplitude_frac"
  YAML::Node values;               // a non-empty list
  // The mappings its values create, the condition lacking them ("schedule" for
  // `schedule.period` in a condition without a schedule).
  std::vector<std::string> created;
};

// A condition as the spec writes it.
struct SpecCondition {
  std::string path;  // "conditions[1]"
  YAML::Node node;
  std::optional<std::string> name;      // given
  std::optional<YAML::Node> name_node;  // where it was given
  YAML::Node run_keys;                  // a mapping: its run config's keys, as written
  std::vector<SpecGridKey> grid;        // whose values place without error in `run_keys`
};

// The base of every run: the spec's top-level run config keys with their values, in order.
using SpecBase = std::vector<std::pair<std::string, YAML::Node>>;

// Whether a condition's value of the base key `key` merges with the base's key by key (the
// mappings context, evaluation, ppo and coverage) rather than replacing it.
bool IsMergedKey(absl::string_view key);

// What is wrong with `name` as a condition's or a sweep's name ("may not ..."), or empty.
std::string NameProblem(absl::string_view name);

class SweepExpansion {
 public:
  // Names the spec `where` in errors. Borrows `base` and `arena` (which holds the spec).
  SweepExpansion(std::string where, const SpecBase& base, YamlArena& arena)
      : reader_(std::move(where)), base_(base), arena_(arena) {}

  SweepExpansion(const SweepExpansion&) = delete;
  SweepExpansion& operator=(const SweepExpansion&) = delete;

  // Appends the trials of `condition` to trials(): each combination of its grid's values (the
  // first key slowest) in each of `modes` in order, its run config validated. Returns the
  // problems found, each INVALID_ARGUMENT as run/config_errors.h: a name not allowed or taken
  // by an earlier condition; the first error of each trial's run config (several trials may
  // give the same one).
  std::vector<absl::Status> Expand(const SpecCondition& condition,
                                   absl::Span<const SpecMode> modes);

  std::vector<SweepTrial>& trials() { return trials_; }

 private:
  // Where a trial's fields were written in the spec: a rule maps a path of the trial's run
  // config (`from`), and unless `exact` the paths below it, to a path of the spec (`to`).
  struct PathRule {
    std::string from;
    std::string to;
    bool exact = false;
  };

  // Whether a condition's mapping at `key` merges with the base's.
  bool MergesWithBase(absl::string_view key) const;
  // The rules for the keys `condition` writes and the mappings its grid creates.
  std::vector<PathRule> ConditionRules(const SpecCondition& condition) const;
  // The trials of one combination, named `name`, its run keys `run_keys`.
  void AddCondition(const SpecCondition& condition, const YAML::Node& run_keys,
                    const std::vector<PathRule>& rules, const std::string& name,
                    absl::Span<const SpecMode> modes, std::vector<absl::Status>& problems);
  // The run config of a trial: the base with `run_keys` over it, in `mode`.
  YAML::Node TrialDocument(const YAML::Node& run_keys, const SpecMode& mode);
  static std::string ShownPath(const std::vector<PathRule>& rules, absl::string_view path);

  YamlReader reader_;  // for errors at the spec's nodes
  const SpecBase& base_;
  YamlArena& arena_;
  std::vector<SweepTrial> trials_;
  // Each condition's name, and where it was given (path and node).
  std::map<std::string, std::pair<std::string, YAML::Node>> names_;
};

}  // namespace dcs::run::internal

#endif  // DCS_RUN_SWEEP_EXPANSION_H_
