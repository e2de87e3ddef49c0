// Copyright 2026 The DCS Authors.
#include "run/sweep_expansion.h"

#include <algorithm>
#include <optional>
#include <set>

#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/status/statusor.h"
#include "env/schedule_config.h"
#include "env/schedule_spec.h"
#include "run/config_errors.h"
#include "run/run_spec.h"
#include "run/run_spec_yaml.h"

// Nodes are never assigned, only constructed, inserted or emplaced (run/yaml_splice.h).

namespace dcs::run::internal {
namespace {

// The base keys whose mappings merge key by key with a condition's.
constexpr absl::string_view kMergedKeys[] = {"context", "evaluation", "ppo", "coverage"};

// The name of a condition that gives none, from its run keys: "static", its schedule's
// family, or its stages' families joined by '>', as written ("?" where one is missing).
std::string DerivedName(const YAML::Node& run_keys) {
  auto family = [](const std::optional<YAML::Node>& schedule) -> std::string {
    const std::optional<YAML::Node> name =
        schedule.has_value() ? FindKey(*schedule, "family") : std::nullopt;
    return name.has_value() && name->IsScalar() ? name->Scalar() : "?";
  };
  if (std::optional<YAML::Node> schedule = FindKey(run_keys, "schedule")) return family(schedule);
  const std::optional<YAML::Node> stages = FindKey(run_keys, "stages");
  if (!stages.has_value() || !stages->IsSequence() || stages->size() == 0) return "static";
  std::vector<std::string> families;
  for (const auto& stage : *stages) families.push_back(family(FindKey(stage, "schedule")));
  return absl::StrJoin(families, ">");
}

// The family of a valid run's trial: "static", "multi_stage", or its one schedule's family as
// env::ScheduleFamilyName spells it.
std::string FamilyOf(const RunSpec& spec) {
  if (spec.stages.empty()) return "static";
  if (spec.stages.size() > 1) return "multi_stage";
  absl::StatusOr<env::ScheduleSpec> schedule =
      env::ParseScheduleSpec(spec.stages[0].schedule, spec.range_lo, spec.range_hi, 0);
  return schedule.ok() ? std::string(env::ScheduleFamilyName(schedule->family()))
                       : spec.stages[0].schedule.family;
}

}  // namespace

bool IsMergedKey(absl::string_view key) {
  return std::find(std::begin(kMergedKeys), std::end(kMergedKeys), key) != std::end(kMergedKeys);
}

std::string NameProblem(absl::string_view name) {
  if (name.empty()) return "may not be empty";
  for (char c : name) {
    if (c == '/') return "may not hold '/' (names become file names)";
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      return "may not hold control characters (a newline, a tab, ...)";
    }
  }
  return "";
}

std::vector<absl::Status> SweepExpansion::Expand(const SpecCondition& condition,
                                                 absl::Span<const SpecMode> modes) {
  std::vector<absl::Status> problems;
  const std::vector<PathRule> rules = ConditionRules(condition);
  // Each combination of its grid's values, the last key fastest.
  std::vector<size_t> at(condition.grid.size(), 0);
  while (true) {
    std::optional<YAML::Node> run_keys;
    run_keys.emplace(condition.run_keys);
    std::vector<PathRule> combination_rules = rules;
    std::string suffix;
    for (size_t i = 0; i < condition.grid.size(); ++i) {
      const SpecGridKey& grid = condition.grid[i];
      const YAML::Node value = grid.values[at[i]];
      absl::StatusOr<YAML::Node> placed = WithValueAt(arena_, *run_keys, grid.steps, value);
      if (!placed.ok()) {  // not expected: the reader placed the first value
        problems.push_back(reader_.Error(grid.path, value, placed.status().message()));
        return problems;
      }
      run_keys.emplace(*std::move(placed));
      combination_rules.push_back({.from = grid.key, .to = ItemPath(grid.path, at[i])});
      absl::StrAppend(&suffix, " ", grid.key.substr(grid.key.rfind('.') + 1), "=",
                      FlowText(value));
    }
    AddCondition(condition, *run_keys, combination_rules,
                 absl::StrCat(condition.name.value_or(DerivedName(*run_keys)), suffix), modes,
                 problems);

    size_t k = at.size();
    while (k > 0 && ++at[k - 1] == condition.grid[k - 1].values.size()) at[--k] = 0;
    if (k == 0) return problems;
  }
}

bool SweepExpansion::MergesWithBase(absl::string_view key) const {
  if (!IsMergedKey(key)) return false;
  for (const auto& [base_key, value] : base_) {
    if (base_key == key) return value.IsMap();
  }
  return false;
}

std::vector<SweepExpansion::PathRule> SweepExpansion::ConditionRules(
    const SpecCondition& condition) const {
  // A key the condition gives replaces the base's, so all below it is the condition's, except
  // in a mapping merged with the base's, where only its keys are.
  std::vector<PathRule> rules;
  for (const auto& entry : condition.run_keys) {
    const std::string key = entry.first.Scalar();
    const std::string path = KeyPath(condition.path, key);
    if (!MergesWithBase(key) || !entry.second.IsMap()) {
      rules.push_back({.from = key, .to = path});
      continue;
    }
    rules.push_back({.from = key, .to = path, .exact = true});
    for (const auto& inner : entry.second) {
      if (!inner.first.IsScalar()) continue;
      rules.push_back({.from = KeyPath(key, inner.first.Scalar()),
                       .to = KeyPath(path, inner.first.Scalar())});
    }
  }
  // A mapping a grid key creates is the grid key's (a merged one only itself).
  for (const SpecGridKey& grid : condition.grid) {
    for (const std::string& created : grid.created) {
      rules.push_back({.from = created, .to = grid.path, .exact = MergesWithBase(created)});
    }
  }
  return rules;
}

void SweepExpansion::AddCondition(const SpecCondition& condition, const YAML::Node& run_keys,
                                  const std::vector<PathRule>& rules, const std::string& name,
                                  absl::Span<const SpecMode> modes,
                                  std::vector<absl::Status>& problems) {
  const std::string name_path =
      condition.name.has_value() ? KeyPath(condition.path, "name") : condition.path;
  const YAML::Node name_node = condition.name_node.value_or(condition.node);
  if (std::string problem = NameProblem(name); !problem.empty()) {
    problems.push_back(reader_.Error(
        name_path, name_node, absl::StrCat("its name '", absl::CHexEscape(name), "' ", problem)));
    return;
  }
  if (auto [it, added] = names_.try_emplace(name, name_path, name_node); !added) {
    const auto& [other_path, other_node] = it->second;
    problems.push_back(reader_.Error(
        name_path, name_node,
        absl::StrCat("duplicate condition name '", name, "' (also ", other_path,
                     other_node.Mark().is_null()
                         ? ""
                         : absl::StrCat(", line ", other_node.Mark().line + 1),
                     "): condition names must be unique",
                     condition.name.has_value() ? "" : "; give one of them a name")));
    return;
  }

  for (const SpecMode& mode : modes) {
    const YAML::Node document = TrialDocument(run_keys, mode);
    std::vector<PathRule> trial_rules = rules;
    trial_rules.push_back({.from = "observe", .to = mode.path});
    YamlReader reader(reader_.where(), [&trial_rules](absl::string_view path) {
      return ShownPath(trial_rules, path);
    });
    ConfigProblems run_problems;
    std::optional<RunSpec> run = ReadRunSpec(reader, document, run_problems);
    if (!run.has_value()) {
      problems.insert(problems.end(), run_problems.problems().begin(),
                      run_problems.problems().end());
      continue;
    }
    trials_.push_back({.condition = name,
                       .family = FamilyOf(*run),
                       .observe = mode.mode,
                       .config = YamlText(document),
                       .spec = *std::move(run)});
  }
}

YAML::Node SweepExpansion::TrialDocument(const YAML::Node& run_keys, const SpecMode& mode) {
  YAML::Node document = arena_.New(YAML::NodeType::Map);
  std::set<std::string> base_keys;
  for (const auto& [key, value] : base_) {
    base_keys.insert(key);
    const std::optional<YAML::Node> over = FindKey(run_keys, key);
    if (!over.has_value()) {
      document.force_insert(key, value);
    } else if (IsMergedKey(key) && value.IsMap() && over->IsMap()) {
      document.force_insert(key, MergedMapping(arena_, value, *over));
    } else {
      document.force_insert(key, *over);
    }
  }
  for (const auto& entry : run_keys) {
    if (!base_keys.contains(entry.first.Scalar())) {
      document.force_insert(entry.first, entry.second);
    }
  }
  document.force_insert("observe", mode.node);
  return document;
}

std::string SweepExpansion::ShownPath(const std::vector<PathRule>& rules,
                                      absl::string_view path) {
  // The longest rule that covers `path` wins; a path no rule covers is a base key's, written
  // where it is.
  const PathRule* best = nullptr;
  for (const PathRule& rule : rules) {
    const std::string& from = rule.from;
    const bool covers =
        path == from || (!rule.exact && absl::StartsWith(path, from) &&
                         (path[from.size()] == '.' || path[from.size()] == '['));
    if (covers && (best == nullptr || from.size() > best->from.size())) best = &rule;
  }
  if (best == nullptr) return std::string(path);
  return absl::StrCat(best->to, path.substr(best->from.size()));
}

}  // namespace dcs::run::internal
