// Copyright 2026 The DCS Authors.
#include "run/sweep_spec_yaml.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/enum_names.h"
#include "run/config_errors.h"
#include "run/config_keys.h"
#include "run/run_spec_yaml.h"
#include "run/sweep_expansion.h"
#include "run/yaml_reader.h"
#include "run/yaml_splice.h"

// Nodes are never assigned, only constructed, inserted or emplaced (run/yaml_splice.h).

namespace dcs::run {
namespace {

using internal::NameProblem;
using internal::SpecCondition;
using internal::SpecGridKey;
using internal::SpecMode;

constexpr int64_t kMaxRuns = 10'000;

// The observation mode of every condition of a sweep that gives none.
constexpr env::ObserveMode kDefaultMode = env::ObserveMode::kNone;

// The run config's keys a sweep gives in a way of its own: `seeds` instead of `seed`, its
// modes for `observe`, and each condition its schedule or stages.
constexpr absl::string_view kSweepOwnRunKeys[] = {"seed", "observe"};
constexpr absl::string_view kConditionScheduleKeys[] = {"schedule", "stages"};

bool Contains(absl::Span<const absl::string_view> names, absl::string_view name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// A sweep spec's keys (run/config_keys.h), the run config's among them taken from its table
// (run/run_spec_yaml.h), in its order.
struct SweepKeys {
  KeyTable<SweepSpec> top_level;
  KeyTable<SweepSpec> condition;
  // The run config's keys the top level gives as the base of every run (a condition may
  // override each), and those a condition gives (its grid varies them).
  std::vector<absl::string_view> base;
  std::vector<absl::string_view> condition_run;
};

const SweepKeys& Keys() {
  static const SweepKeys* const keys = [] {
    std::vector<absl::string_view> base;
    for (absl::string_view key : RunConfigKeys().names()) {
      if (!Contains(kSweepOwnRunKeys, key) && !Contains(kConditionScheduleKeys, key)) {
        base.push_back(key);
      }
    }
    std::vector<absl::string_view> condition_run(std::begin(kConditionScheduleKeys),
                                                 std::end(kConditionScheduleKeys));
    condition_run.insert(condition_run.end(), base.begin(), base.end());

    const std::string modes = absl::StrCat(
        "one of {", absl::StrJoin(NamesOf(env::kObserveModeNames), ", "), "}, or a list of them");
    std::vector<ConfigKey<SweepSpec>> top = {
        {.name = "name",
         .meaning = "the sweep's name",
         .type = "string",
         .default_value = "none (dcs submit: the file's name)"},
        {.name = "seeds",
         .meaning = "N for seeds 0..N-1, or a list of distinct seeds: each trial runs once with "
                    "each",
         .bound = AtLeast(1),
         .type = "integer, or list of integers",
         .default_value = "required"},
        {.name = "observe",
         .meaning = "the observation modes every condition runs in, in order",
         .type = modes,
         .default_value = absl::StrCat("[", NameOf(env::kObserveModeNames, kDefaultMode), "]")},
        {.name = "conditions",
         .meaning = absl::StrCat("the conditions, in order; at most ", kMaxRuns,
                                 " runs in all (trials times seeds)"),
         .type = "list of conditions",
         .default_value = "required"},
    };
    std::vector<ConfigKey<SweepSpec>> condition = {
        {.name = "name",
         .meaning = "the condition's name: by default \"static\", its schedule's family, or its "
                    "stages' families joined by '>'",
         .type = "string",
         .default_value = "derived"},
        {.name = "grid",
         .meaning = "key paths of its run config to lists of values: a condition per "
                    "combination, the first key slowest",
         .type = "mapping of key paths to lists",
         .default_value = "none"},
        {.name = "observe",
         .meaning = "the condition's own modes, instead of the sweep's",
         .type = modes,
         .default_value = "the sweep's"},
    };
    for (absl::string_view key : kConditionScheduleKeys) {
      const ConfigKey<RunSpec>& run = RunConfigKeys()[key];
      condition.push_back({.name = key,
                           .meaning = run.meaning,
                           .type = run.type,
                           .default_value = run.default_value});
    }
    for (absl::string_view key : base) {
      top.push_back({.name = key,
                     .meaning = "the base of every run",
                     .type = "as in a run config",
                     .default_value = "the run config's"});
      condition.push_back(
          {.name = key,
           .meaning = internal::IsMergedKey(key) ? "merged into the base's, key by key"
                                                 : "replaces the base's",
           .type = "as in a run config",
           .default_value = "the base's"});
    }
    top.push_back({.name = "study",
                   .meaning = "makes the sweep a search over its one condition's run config "
                              "(coordinator/study_sweep_spec.h)",
                   .type = "mapping",
                   .default_value = "none"});
    return new SweepKeys{.top_level = KeyTable<SweepSpec>(std::move(top)),
                         .condition = KeyTable<SweepSpec>(std::move(condition)),
                         .base = std::move(base),
                         .condition_run = std::move(condition_run)};
  }();
  return *keys;
}

// `a * b`, at most kCountCap (counts of trials and runs, refused long before).
constexpr int64_t kCountCap = int64_t{1} << 50;
int64_t Times(int64_t a, int64_t b) {
  return (b != 0 && a > kCountCap / b) ? kCountCap : std::min(a * b, kCountCap);
}

// A condition as read.
struct Condition {
  SpecCondition spec;
  std::optional<std::vector<SpecMode>> modes;  // its own
  int64_t count = 1;                           // combinations of its grid's values
  bool ok = true;                              // no problem found in it
};

// Reads one sweep spec, collecting its problems rather than stopping at the first.
class SweepParser {
 public:
  explicit SweepParser(const YamlReader& reader) : where_(reader.where()), reader_(reader) {}

  absl::StatusOr<SweepSpec> ReadSpec(const YAML::Node& root);

 private:
  // Calls `read(key, key_node, value, key_path)` for each entry of the mapping `node` at `path`;
  // a key that is no name, or is repeated, is a problem and skipped. False if there was such a
  // problem or `node` is not a mapping (`what` says what it should be).
  template <typename Read>
  bool Entries(const YAML::Node& node, const std::string& path, absl::string_view what,
               Read read);
  void Problem(const std::string& path, const YAML::Node& node, absl::string_view message);
  void Problem(const absl::Status& status);
  void UnknownKey(const std::string& key_path, const YAML::Node& key_node,
                  absl::string_view where, absl::Span<const absl::string_view> allowed);

  void TopLevel(const YAML::Node& root);
  void Seeds(const YAML::Node& node, const std::string& path);
  std::optional<std::vector<SpecMode>> Modes(const YAML::Node& node, const std::string& path);
  void Conditions(const YAML::Node& node);
  void ReadCondition(const YAML::Node& node, const std::string& path);
  void ReadGrid(const YAML::Node& node, const std::string& path, Condition& condition);
  int64_t SeedCount() const;
  // The modes `condition` runs in: its own, else the sweep's; null if those are wrong.
  const std::vector<SpecMode>* ModesOf(const Condition& condition) const;
  void CheckRuns();

  std::string where_;
  const YamlReader& reader_;
  std::optional<YamlArena> arena_;  // of the spec's document
  ConfigProblems problems_;

  // Read from the top level.
  std::string name_;
  bool has_seeds_ = false;
  bool study_ = false;
  int64_t seed_count_ = 0;                      // seeds: N
  std::optional<std::vector<uint64_t>> seeds_;  // seeds: [...]
  bool has_modes_ = false;
  std::optional<std::vector<SpecMode>> modes_;  // the sweep's, if valid
  internal::SpecBase base_;
  std::optional<YAML::Node> conditions_node_;
  std::vector<Condition> conditions_;
};

template <typename Read>
bool SweepParser::Entries(const YAML::Node& node, const std::string& path, absl::string_view what,
                          Read read) {
  if (!node.IsMap()) {
    Problem(path, node, absl::StrCat(path.empty() ? "the document" : path, " must be ", what));
    return false;
  }
  bool clean = true;
  std::set<std::string> seen;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) {
      Problem(path, entry.first, "a key must be a name, not a list or mapping");
      clean = false;
      continue;
    }
    const std::string key = entry.first.Scalar();
    const std::string key_path = KeyPath(path, key);
    if (!seen.insert(key).second) {
      Problem(key_path, entry.first, absl::StrCat("key '", key, "' given twice"));
      clean = false;
      continue;
    }
    read(key, entry.first, entry.second, key_path);
  }
  return clean;
}

void SweepParser::Problem(const std::string& path, const YAML::Node& node,
                          absl::string_view message) {
  Problem(reader_.Error(path, node, message));
}

void SweepParser::Problem(const absl::Status& status) { problems_.Add(status); }

void SweepParser::UnknownKey(const std::string& key_path, const YAML::Node& key_node,
                             absl::string_view where,
                             absl::Span<const absl::string_view> allowed) {
  Problem(key_path, key_node,
          absl::StrCat("unknown key '", key_node.Scalar(), "' ", where, " (allowed: ",
                       absl::StrJoin(allowed, ", "), ")"));
}

void SweepParser::TopLevel(const YAML::Node& root) {
  Entries(root, "", "a mapping",
          [&](const std::string& key, const YAML::Node& key_node, const YAML::Node& value,
              const std::string& path) {
            if (key == "name") {
              absl::StatusOr<std::string> name = reader_.Word(value, path);
              if (!name.ok()) return Problem(name.status());
              if (std::string problem = NameProblem(*name); !problem.empty()) {
                return Problem(path, value, absl::StrCat("a name ", problem));
              }
              name_ = *name;
            } else if (key == "seeds") {
              has_seeds_ = true;
              Seeds(value, path);
            } else if (key == "observe") {
              has_modes_ = true;
              if (std::optional<std::vector<SpecMode>> modes = Modes(value, path)) {
                modes_.emplace(*std::move(modes));
              }
            } else if (key == "conditions") {
              conditions_node_.emplace(value);
            } else if (key == "study") {
              if (value.IsMap()) {
                study_ = true;
              } else {
                Problem(path, value, "must be a mapping: the study's trials, sampler and space");
              }
            } else if (Contains(Keys().base, key)) {
              base_.emplace_back(key, value);
            } else if (key == "seed") {
              Problem(path, key_node,
                      "a sweep gives 'seeds' (N for seeds 0..N-1, or a list of seeds), not "
                      "'seed': each run gets one of them");
            } else if (key == "schedule" || key == "stages") {
              Problem(path, key_node,
                      absl::StrCat("'", key,
                                   "' belongs to a condition, not the top level: conditions "
                                   "differ in their schedules (conditions: [{",
                                   key, ": ...}])"));
            } else {
              UnknownKey(path, key_node, "at the top level", Keys().top_level.names());
            }
          });
}

void SweepParser::Seeds(const YAML::Node& node, const std::string& path) {
  if (node.IsSequence()) {
    if (node.size() == 0) return Problem(path, node, "must list at least one seed");
    std::vector<uint64_t> seeds;
    std::map<uint64_t, std::string> seen;
    for (size_t i = 0; i < node.size(); ++i) {
      const std::string item_path = ItemPath(path, i);
      absl::StatusOr<uint64_t> seed = reader_.Uint64(node[i], item_path);
      if (!seed.ok()) {
        Problem(seed.status());
      } else if (auto [it, added] = seen.emplace(*seed, item_path); !added) {
        Problem(item_path, node[i],
                absl::StrCat("seed ", *seed, " is listed twice (also ", it->second, ")"));
      } else {
        seeds.push_back(*seed);
      }
    }
    if (seeds.size() == node.size()) seeds_.emplace(std::move(seeds));
    return;
  }
  if (!node.IsScalar()) {
    return Problem(path, node,
                   "must be a number of seeds N (seeds 0..N-1) or a list of distinct seeds");
  }
  absl::StatusOr<int64_t> count = reader_.Int64(node, path);
  if (!count.ok()) return Problem(count.status());
  if (const Bound& bound = Keys().top_level["seeds"].bound; !bound.Contains(*count)) {
    return Problem(path, node, absl::StrCat("must be ", bound.Rule(), ", got ", *count));
  }
  seed_count_ = *count;  // listed once CheckRuns has found it small enough
}

std::optional<std::vector<SpecMode>> SweepParser::Modes(const YAML::Node& node,
                                                        const std::string& path) {
  const std::string allowed = ListNames(env::kObserveModeNames);
  std::vector<SpecMode> modes;
  auto read = [&](const YAML::Node& item, const std::string& item_path) {
    absl::StatusOr<std::string> word = reader_.Word(item, item_path);
    if (!word.ok()) return Problem(word.status());
    const std::optional<env::ObserveMode> mode = FindByName(env::kObserveModeNames, *word);
    if (!mode.has_value()) {
      return Problem(item_path, item, absl::StrCat("must be ", allowed, ", got '", *word, "'"));
    }
    for (const SpecMode& other : modes) {
      if (other.mode == *mode) {
        return Problem(item_path, item,
                       absl::StrCat("mode ", *word, " is listed twice (also ", other.path, ")"));
      }
    }
    modes.push_back({.mode = *mode, .node = item, .path = item_path});
  };
  size_t given = 1;
  if (node.IsSequence()) {
    given = node.size();
    if (given == 0) {
      Problem(path, node, absl::StrCat("must list at least one mode (", allowed, ")"));
    }
    for (size_t i = 0; i < node.size(); ++i) read(node[i], ItemPath(path, i));
  } else if (node.IsScalar()) {
    read(node, path);
  } else {
    Problem(path, node, absl::StrCat("must be a mode (", allowed, ") or a list of them"));
    return std::nullopt;
  }
  if (given == 0 || modes.size() != given) return std::nullopt;
  return modes;
}

void SweepParser::Conditions(const YAML::Node& node) {
  if (!node.IsSequence()) {
    return Problem("conditions", node,
                   "must be a list of conditions (e.g. [{name: static}, {schedule: ...}])");
  }
  if (node.size() == 0) {
    return Problem("conditions", node,
                   "needs at least one condition: an empty grid makes no runs");
  }
  for (size_t i = 0; i < node.size(); ++i) ReadCondition(node[i], ItemPath("conditions", i));
}

void SweepParser::ReadCondition(const YAML::Node& node, const std::string& path) {
  Condition condition{
      .spec = {.path = path, .node = node, .run_keys = arena_->New(YAML::NodeType::Map)}};
  std::optional<std::pair<YAML::Node, std::string>> grid;
  const bool clean = Entries(
      node, path, "a condition: a mapping of name, schedule or stages, grid, observe, base keys",
      [&](const std::string& key, const YAML::Node& key_node, const YAML::Node& value,
          const std::string& key_path) {
        if (key == "name") {
          absl::StatusOr<std::string> name = reader_.Word(value, key_path);
          condition.ok = condition.ok && name.ok();
          if (!name.ok()) return Problem(name.status());
          if (std::string problem = NameProblem(*name); !problem.empty()) {
            condition.ok = false;
            return Problem(key_path, value, absl::StrCat("a name ", problem));
          }
          condition.spec.name = *name;
          condition.spec.name_node.emplace(value);
        } else if (key == "grid") {
          grid.emplace(value, key_path);
        } else if (key == "observe") {
          if (std::optional<std::vector<SpecMode>> modes = Modes(value, key_path)) {
            condition.modes.emplace(*std::move(modes));
          } else {
            condition.ok = false;
          }
        } else if (Contains(Keys().condition_run, key)) {
          condition.spec.run_keys.force_insert(key_node, value);
        } else if (key == "seed") {
          condition.ok = false;
          Problem(key_path, key_node,
                  "seeds are the sweep's ('seeds' at the top level): every condition runs "
                  "with each of them");
        } else {
          condition.ok = false;
          UnknownKey(key_path, key_node, absl::StrCat("in ", path), Keys().condition.names());
        }
      });
  condition.ok = condition.ok && clean;
  if (grid.has_value()) ReadGrid(grid->first, grid->second, condition);
  conditions_.push_back(std::move(condition));
}

void SweepParser::ReadGrid(const YAML::Node& node, const std::string& path,
                           Condition& condition) {
  // The condition's keys with each grid key's first value placed: where the next key goes.
  std::optional<YAML::Node> placed;
  placed.emplace(condition.spec.run_keys);
  const bool clean = Entries(
      node, path, "a mapping of key paths to lists of values (e.g. {schedule.period: [100, 200]})",
      [&](const std::string& key, const YAML::Node& key_node, const YAML::Node& values,
          const std::string& key_path) {
        const int reported = problems_.reported();
        std::optional<std::vector<KeyPathStep>> steps = ParseKeyPath(key);
        if (!steps.has_value()) {
          Problem(key_path, key_node,
                  absl::StrCat("'", key,
                               "' is not a key path: names joined by '.', list items as [i] "
                               "(e.g. schedule.period, stages[1].steps)"));
        } else if (!Contains(Keys().condition_run, steps->front().key)) {
          Problem(key_path, key_node,
                  absl::StrCat("a grid varies keys of the condition's run config (",
                               absl::StrJoin(Keys().condition_run, ", "), "), not '",
                               steps->front().key, "'"));
        } else {
          for (const SpecGridKey& other : condition.spec.grid) {
            if (KeyPathsOverlap(*steps, other.steps)) {
              Problem(key_path, key_node,
                      absl::StrCat("overlaps grid key '", other.key,
                                   "': values placed at both would overwrite one another"));
            }
          }
        }
        if (!values.IsSequence()) {
          Problem(key_path, values, "must be a list of values (one condition each)");
        } else if (values.size() == 0) {
          Problem(key_path, values, "must list at least one value: an empty list makes no "
                                    "conditions");
        } else {
          std::map<std::string, size_t> seen;
          for (size_t i = 0; i < values.size(); ++i) {
            auto [it, added] = seen.emplace(FlowText(values[i]), i);
            if (!added) {
              Problem(ItemPath(key_path, i), values[i],
                      absl::StrCat("'", it->first, "' is listed twice (also ",
                                   ItemPath(key_path, it->second),
                                   "): it would make two conditions of one name"));
            }
          }
        }
        std::vector<std::string> created;
        if (problems_.reported() == reported) {
          absl::StatusOr<YAML::Node> next =
              WithValueAt(*arena_, *placed, *steps, values[0], &created);
          if (next.ok()) {
            placed.emplace(*std::move(next));
          } else {
            Problem(key_path, key_node,
                    absl::StrCat("cannot place its values in the condition: ",
                                 next.status().message()));
          }
        }
        if (problems_.reported() != reported) {
          condition.ok = false;
          return;
        }
        condition.spec.grid.push_back({.key = key,
                                       .steps = *std::move(steps),
                                       .path = key_path,
                                       .values = values,
                                       .created = std::move(created)});
        condition.count = Times(condition.count, static_cast<int64_t>(values.size()));
      });
  if (node.IsMap() && node.size() == 0) {
    Problem(path, node, "must map at least one key path to values (or be left out)");
  }
  condition.ok = condition.ok && clean && node.IsMap() && node.size() > 0;
}

int64_t SweepParser::SeedCount() const {
  if (seeds_.has_value()) return static_cast<int64_t>(seeds_->size());
  return seed_count_;
}

const std::vector<SpecMode>* SweepParser::ModesOf(const Condition& condition) const {
  if (condition.modes.has_value()) return &*condition.modes;
  return modes_.has_value() ? &*modes_ : nullptr;
}

void SweepParser::CheckRuns() {
  int64_t trials = 0;
  for (const Condition& condition : conditions_) {
    const std::vector<SpecMode>* modes = ModesOf(condition);
    const int64_t mode_count = modes != nullptr ? static_cast<int64_t>(modes->size()) : 1;
    trials = std::min(kCountCap, trials + Times(condition.count, mode_count));
  }
  const int64_t seeds = std::max<int64_t>(SeedCount(), 1);
  const int64_t runs = Times(trials, seeds);
  if (runs <= kMaxRuns) return;
  Problem("conditions", *conditions_node_,
          absl::StrCat(trials, " trials x ", seeds, " seeds would make ",
                       runs == kCountCap ? "more than " : "", runs,
                       " runs; a sweep may make at most ", kMaxRuns));
}

absl::StatusOr<SweepSpec> SweepParser::ReadSpec(const YAML::Node& root) {
  if (!root.IsMap()) {
    return reader_.Error("", root, "the document must be a sweep spec: a mapping with seeds, "
                                   "conditions and the runs' base keys");
  }
  arena_.emplace(root);
  SweepSpec spec;
  try {
    TopLevel(root);
    if (!has_seeds_) {
      Problem(reader_.errors().At(
          "seeds", "missing: give the number of seeds N (seeds 0..N-1) or a list of seeds"));
    }
    if (!has_modes_) {
      modes_.emplace();
      modes_->push_back(
          {.mode = kDefaultMode,
           .node = YAML::Node(std::string(NameOf(env::kObserveModeNames, kDefaultMode))),
           .path = "observe"});
    }
    if (!conditions_node_.has_value()) {
      Problem(reader_.errors().At(
          "conditions", "missing: a sweep needs at least one condition (e.g. [{name: static}])"));
    } else {
      Conditions(*conditions_node_);
      const int reported = problems_.reported();
      CheckRuns();
      if (problems_.reported() == reported) {
        internal::SweepExpansion expansion(where_, base_, *arena_);
        for (const Condition& condition : conditions_) {
          if (!condition.ok) continue;
          const std::vector<SpecMode>* modes = ModesOf(condition);
          for (const absl::Status& problem :
               expansion.Expand(condition.spec, modes != nullptr
                                                    ? absl::Span<const SpecMode>(*modes)
                                                    : absl::Span<const SpecMode>())) {
            Problem(problem);
          }
        }
        spec.trials = std::move(expansion.trials());
      }
    }
  } catch (const YAML::Exception& e) {  // not expected: every access is checked first
    return absl::InvalidArgumentError(absl::StrCat(where_, ": line ", e.mark.line + 1,
                                                   ", column ", e.mark.column + 1, ": ", e.msg));
  }
  if (!problems_.empty()) return problems_.ToStatus(where_);

  spec.name = name_;
  spec.study = study_;
  if (seeds_.has_value()) {
    spec.seeds = *seeds_;
  } else {
    for (int64_t seed = 0; seed < seed_count_; ++seed) {
      spec.seeds.push_back(static_cast<uint64_t>(seed));
    }
  }
  for (const SweepTrial& trial : spec.trials) {
    if (trial.family == "static") {
      spec.baseline = trial.condition;
      break;
    }
  }
  return spec;
}

}  // namespace

std::vector<KeySection> SweepSpecReference() {
  return {{"", Describe(Keys().top_level)}, {"conditions[i]", Describe(Keys().condition)}};
}

absl::StatusOr<SweepSpec> ParseSweepSpecYaml(absl::string_view text, absl::string_view where) {
  const YamlReader reader{std::string(where)};
  absl::StatusOr<YAML::Node> root = reader.Load(text);
  if (!root.ok()) return root.status();
  return ReadSweepSpec(reader, *root);
}

absl::StatusOr<SweepSpec> ReadSweepSpec(const YamlReader& reader, const YAML::Node& root) {
  return SweepParser(reader).ReadSpec(root);
}

}  // namespace dcs::run
