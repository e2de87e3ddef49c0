// Copyright 2026 The DCS Authors.
#include "run/run_spec_yaml.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <type_traits>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/context_feature.h"
#include "env/env_registry.h"
#include "env/schedule_config.h"
#include "run/config_keys.h"
#include "run/coverage.h"
#include "run/ppo_config.h"
#include "run/schedule_yaml.h"
#include "run/yaml_reader.h"

namespace dcs::run {
namespace {

constexpr int kMaxPoolSize = 10'000;  // env::ContextPool::OfSize's limit

// The YAML path of stage `index`'s schedule: `schedule` when the config gave one schedule for
// the whole run, `stages[i].schedule` otherwise.
std::string SchedulePath(size_t index, bool schedule_key) {
  return schedule_key ? std::string("schedule")
                      : absl::StrCat(ItemPath("stages", index), ".schedule");
}

// "one of {a, b, c}", as the reference writes a word from a fixed list.
template <typename Names>
std::string OneOf(const Names& names) {
  return absl::StrCat("one of {", absl::StrJoin(names, ", "), "}");
}

// ---------------------------------------------------------------------------------------------
// The keys, one table per mapping (run/config_keys.h).

const KeyTable<RunSpec>& PoolKeys() {
  static const KeyTable<RunSpec>* const keys = new KeyTable<RunSpec>({
      {.name = "size",
       .meaning = "that many values spread evenly over the training range (1: its midpoint)",
       .field = &RunSpec::pool_size,
       .bound = Within(1, kMaxPoolSize)},
      {.name = "values",
       .meaning = "exactly these values, each within the training range",
       .field = &RunSpec::pool_values,
       .default_value = "none"},
  });
  return *keys;
}

const KeyTable<RunSpec::Stage>& StageKeys() {
  static const KeyTable<RunSpec::Stage>* const keys = new KeyTable<RunSpec::Stage>({
      {.name = "steps",
       .meaning = "environment steps the stage runs for; the last one stays in force after them "
                  "(0: a single stage that runs for the whole run)",
       .field = &RunSpec::Stage::steps,
       .bound = AtLeast(1)},
      {.name = "schedule",
       .meaning = "the stage's schedule ({family: constant} for none)",
       .type = "schedule",
       .default_value = "required"},
  });
  return *keys;
}

const KeyTable<RunSpec>& EvaluationKeys() {
  static const KeyTable<RunSpec>* const keys = new KeyTable<RunSpec>({
      {.name = "freq",
       .meaning = "environment steps between evaluations (also one at each stage boundary and "
                  "at the end)",
       .field = &RunSpec::eval_freq,
       .bound = AtLeast(1)},
      {.name = "episodes",
       .meaning = "deterministic episodes per evaluation context",
       .field = &RunSpec::eval_episodes,
       .bound = AtLeast(1)},
      {.name = "contexts",
       .meaning = "the varied feature's values evaluated, by split: at least one",
       .type = "mapping",
       .default_value = "required"},
  });
  return *keys;
}

std::string SplitMeaning(actor::Split split) {
  switch (split) {
    case actor::Split::kId:
      return "values inside the training range";
    case actor::Split::kOodLow:
      return "values below it (out of distribution)";
    case actor::Split::kOodHigh:
      return "values above it (out of distribution)";
  }
  return "";
}

// Keyed by the splits' names (actor/split.h).
const KeyTable<RunSpec>& EvaluationContextKeys() {
  static const KeyTable<RunSpec>* const keys = [] {
    std::vector<ConfigKey<RunSpec>> splits;
    for (const auto& [split, name] : actor::kSplitNames) {
      splits.push_back({.name = name,
                        .meaning = SplitMeaning(split),
                        .type = "list of numbers",
                        .default_value = "[]"});
    }
    return new KeyTable<RunSpec>(std::move(splits));
  }();
  return *keys;
}

const KeyTable<CoverageSpec>& CoverageKeys() {
  static const KeyTable<CoverageSpec>* const keys = new KeyTable<CoverageSpec>({
      {.name = "window",
       .meaning = "environment steps per window of counted cells",
       .field = &CoverageSpec::window,
       .bound = AtLeast(1)},
      {.name = "projections",
       .meaning = "the environment's state projections counted, by name",
       .type = "list of names",
       .default_value = "[] (every one the environment has)"},
  });
  return *keys;
}

// ---------------------------------------------------------------------------------------------
// Validation.

// Adds `spec`'s problems that need its environment's features and rules to `problems`. An
// unknown feature or an unusable training range stops the checks of values against them (the
// pool, the contexts, the schedules over the range); a context the environment refuses is named
// once, at the first value of the feature it fails with.
void CheckWithEnvironment(const RunSpec& spec, const env::ContextSpace& space,
                          absl::Status (*validate_context)(std::span<const double>),
                          const ConfigErrors& errors, bool schedule_key,
                          ConfigProblems& problems) {
  // The varied feature and its training range.
  absl::StatusOr<int> feature = space.IndexOf(spec.feature);
  if (!feature.ok()) problems.Add(errors.At("feature", feature.status().message()));
  const double lo = spec.range_lo;
  const double hi = spec.range_hi;
  const bool range_ok = std::isfinite(lo) && std::isfinite(hi) && lo < hi;
  if (!range_ok) {
    problems.Add(errors.At(
        "training_range",
        absl::StrCat("must be [lo, hi] with lo < hi, both finite, got [", lo, ", ", hi, "]")));
  }

  // The stages.
  const bool whole_run = spec.stages.size() == 1 && spec.stages[0].steps == 0;
  int64_t start = 0;
  const Bound& steps = StageKeys()["steps"].bound;
  for (size_t i = 0; i < spec.stages.size(); ++i) {
    const RunSpec::Stage& stage = spec.stages[i];
    if (!whole_run && !steps.Contains(static_cast<double>(stage.steps))) {
      problems.Add(errors.At(absl::StrCat(ItemPath("stages", i), ".steps"),
                             absl::StrCat("must be ", steps.Rule(),
                                          " (0 only for a single stage, which then runs for the "
                                          "whole run), got ",
                                          stage.steps)));
    }
    if (i > 0 && start >= spec.total_timesteps) {
      problems.Add(errors.At(
          ItemPath("stages", i),
          absl::StrCat("starts at step ", start, ", not before total_timesteps (",
                       spec.total_timesteps, "): it would never run")));
    }
    start += std::max<int64_t>(stage.steps, 0);
    if (!range_ok) continue;
    for (const absl::Status& problem : env::ScheduleConfigProblems(stage.schedule, lo, hi)) {
      problems.Add(ScheduleError(errors, SchedulePath(i, schedule_key), problem));
    }
  }
  if (!feature.ok() || !range_ok) return;

  bool range_in_bounds = true;
  for (const auto& [value, path] : {std::pair{lo, "training_range[0]"},
                                    std::pair{hi, "training_range[1]"}}) {
    if (absl::Status s = space.Validate(*feature, value); !s.ok()) {
      problems.Add(errors.At(path, s.message()));
      range_in_bounds = false;
    }
  }

  // The other features' values.
  bool context_ok = true;
  if (spec.context.contains(spec.feature)) {
    problems.Add(errors.At(KeyPath("context", spec.feature),
                           absl::StrCat("'", spec.feature,
                                        "' is the varied feature: its values come from "
                                        "training_range, pool and evaluation.contexts")));
    context_ok = false;
  }
  absl::StatusOr<std::vector<double>> values = space.WithValues(spec.context);
  if (!values.ok()) {
    problems.Add(errors.At(KeyPath("context", ErrorField(values.status()).value_or("")),
                           values.status().message()));
    context_ok = false;
  }
  // The full context, at every value the varied feature takes in training and evaluation; once
  // it fails, the other features' values are what is wrong, and one problem says so.
  auto check_full = [&](double value, absl::string_view path) {
    if (!context_ok) return;
    (*values)[*feature] = value;
    if (absl::Status s = validate_context(*values); !s.ok()) {
      problems.Add(errors.At(path, absl::StrCat("the context is invalid with ", spec.feature,
                                                " = ", value, ": ", s.message())));
      context_ok = false;
    }
  };
  if (range_in_bounds) {
    check_full(lo, "context");
    check_full(hi, "context");
  }

  // The pool.
  if (!spec.pool_values.empty()) {
    for (size_t i = 0; i < spec.pool_values.size(); ++i) {
      const double value = spec.pool_values[i];
      const std::string path = ItemPath("pool.values", i);
      if (!(value >= lo && value <= hi)) {
        problems.Add(errors.At(path, absl::StrCat("must be within training_range [", lo, ", ",
                                                  hi, "], got ", value)));
      } else if (range_in_bounds) {
        check_full(value, path);
      }
    }
  } else {
    CheckBounds(PoolKeys(), spec, "pool", errors, problems);
  }

  // The evaluation contexts: physical bounds only (OOD values lie outside the training range).
  for (const auto& [split, name] : actor::kSplitNames) {
    const std::vector<double>& contexts = spec.eval_values(split);
    const std::string split_path = KeyPath("evaluation.contexts", name);
    for (size_t i = 0; i < contexts.size(); ++i) {
      const std::string path = ItemPath(split_path, i);
      if (absl::Status s = space.Validate(*feature, contexts[i]); !s.ok()) {
        problems.Add(errors.At(path, s.message()));
      } else {
        check_full(contexts[i], path);
      }
    }
  }
}

// Adds each of `spec`'s problems to `problems` (ValidateRunSpec's rules). Each field's own
// checks run whatever the others found; an unknown environment stops the checks that need it.
void Validate(const RunSpec& spec, const ConfigErrors& errors, bool schedule_key,
              ConfigProblems& problems) {
  CheckBounds(RunConfigKeys(), spec, "", errors, problems);
  CheckBounds(EvaluationKeys(), spec, "evaluation", errors, problems);
  if (std::all_of(spec.eval_contexts.begin(), spec.eval_contexts.end(),
                  [](const std::vector<double>& values) { return values.empty(); })) {
    problems.Add(errors.At("evaluation.contexts",
                           absl::StrCat("needs at least one evaluation context (in ",
                                        ListNames(actor::kSplitNames), ")")));
  }
  const std::vector<std::string> environments = env::EnvironmentNames();
  if (std::find(environments.begin(), environments.end(), spec.env) == environments.end()) {
    problems.Add(errors.At("env", absl::StrCat("unknown environment '", spec.env, "' (known: ",
                                               absl::StrJoin(environments, ", "), ")")));
  } else {
    problems.Add(env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
      CheckWithEnvironment(spec, Env::Features(), &Env::ValidateContext, errors, schedule_key,
                           problems);
      if (!spec.ppo.context_layers.empty() &&
          !std::is_same_v<typename Env::Observation, uint8_t>) {  // an image's bytes
        problems.Add(errors.At("ppo.context_layers",
                               absl::StrCat("a context branch is for image policies; ",
                                            spec.env, "'s observation has no image")));
      }
      if (!spec.coverage.has_value()) return absl::OkStatus();
      CheckBounds(CoverageKeys(), *spec.coverage, "coverage", errors, problems);
      absl::StatusOr<std::vector<env::StateProjection>> projections =
          SelectProjections(*spec.coverage, EnvironmentProjections<Env>());
      if (!projections.ok()) {
        problems.Add(errors.At("coverage.projections", projections.status().message()));
      }
      return absl::OkStatus();
    }));
  }
  CheckPpoConfig(spec.ppo, spec.n_envs, errors, problems);
}

// ---------------------------------------------------------------------------------------------
// Parsing.

// Reads one document's nodes into a RunSpec; the reader notes the line of every field.
class Parser {
 public:
  explicit Parser(YamlReader& reader) : r_(reader) {}

  // Reads `root`; `schedule_key` tells whether the config gave `schedule` (not `stages`). Each
  // top-level key is read on its own: its problems go to `problems` and the others are read.
  void Document(const YAML::Node& root, RunSpec& spec, bool& schedule_key,
                ConfigProblems& problems);

 private:
  absl::Status Context(const YAML::Node& node, const std::string& path, RunSpec& spec);
  absl::Status Pool(const YAML::Node& node, const std::string& path, RunSpec& spec);
  absl::Status Stages(const YAML::Node& node, RunSpec& spec);
  absl::Status Evaluation(const YAML::Node& node, RunSpec& spec);
  absl::Status Ppo(const YAML::Node& node, PpoConfig& ppo);
  absl::Status Coverage(const YAML::Node& node, RunSpec& spec);

  YamlReader& r_;
};

absl::Status Parser::Context(const YAML::Node& node, const std::string& path, RunSpec& spec) {
  if (!node.IsMap()) return r_.Error(path, node, "must be a mapping of feature names to values");
  return r_.ForEachEntry(node, path,
                         [&](const std::string& name, const YAML::Node& value,
                             const std::string& feature_path) -> absl::Status {
                           DCS_ASSIGN_OR_RETURN(spec.context[name],
                                                r_.Number(value, feature_path));
                           return absl::OkStatus();
                         });
}

absl::Status Parser::Pool(const YAML::Node& node, const std::string& path, RunSpec& spec) {
  bool has_size = false;
  bool has_values = false;
  const KeyTable<RunSpec>& keys = PoolKeys();
  DCS_RETURN_IF_ERROR(r_.ForEachKey(
      node, path, keys.names(),
      [&](const std::string& key, const YAML::Node& value,
          const std::string& key_path) -> absl::Status {
        DCS_RETURN_IF_ERROR(ReadField(r_, keys[key], value, key_path, spec));
        if (key == "size") {
          has_size = true;
          return absl::OkStatus();
        }
        has_values = true;
        if (spec.pool_values.empty()) {
          return r_.Error(key_path, value, "must list at least one value");
        }
        return absl::OkStatus();
      }));
  if (has_size == has_values) {
    return r_.Error(path, node, "must give exactly one of size and values");
  }
  return absl::OkStatus();
}

absl::Status Parser::Stages(const YAML::Node& node, RunSpec& spec) {
  return r_.ForEachItem(
      node, "stages", "a list of {steps: N, schedule: {family: ...}}",
      [&](const YAML::Node& stage_node, const std::string& stage_path) -> absl::Status {
        RunSpec::Stage stage;
        bool has_schedule = false;
        DCS_RETURN_IF_ERROR(r_.ForEachKey(
            stage_node, stage_path, StageKeys().names(),
            [&](const std::string& key, const YAML::Node& value,
                const std::string& path) -> absl::Status {
              if (key == "steps") {
                DCS_RETURN_IF_ERROR(ReadField(r_, StageKeys()[key], value, path, stage));
              } else {
                has_schedule = true;
                DCS_ASSIGN_OR_RETURN(stage.schedule, ReadScheduleConfig(r_, value, path));
              }
              return absl::OkStatus();
            }));
        if (!has_schedule) {
          return r_.Error(stage_path, stage_node,
                          "a stage needs a schedule (e.g. {family: constant} for none)");
        }
        spec.stages.push_back(std::move(stage));
        return absl::OkStatus();
      });
}

absl::Status Parser::Evaluation(const YAML::Node& node, RunSpec& spec) {
  const KeyTable<RunSpec>& keys = EvaluationKeys();
  return r_.ForEachKey(
      node, "evaluation", keys.names(),
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
        if (key != "contexts") {
          DCS_RETURN_IF_ERROR(ReadField(r_, keys[key], value, path, spec));
        } else {
          return r_.ForEachKey(value, path, EvaluationContextKeys().names(),
                               [&](const std::string& split, const YAML::Node& values,
                                   const std::string& split_path) -> absl::Status {
                                 DCS_ASSIGN_OR_RETURN(
                                     spec.eval_values(*FindByName(actor::kSplitNames, split)),
                                     r_.Numbers(values, split_path));
                                 return absl::OkStatus();
                               });
        }
        return absl::OkStatus();
      });
}

absl::Status Parser::Coverage(const YAML::Node& node, RunSpec& spec) {
  RunSpec::Coverage& coverage = spec.coverage.emplace();
  const KeyTable<CoverageSpec>& keys = CoverageKeys();
  return r_.ForEachKey(node, "coverage", keys.names(),
                       [&](const std::string& key, const YAML::Node& value,
                           const std::string& path) -> absl::Status {
                         if (key == "window") {
                           return ReadField(r_, keys[key], value, path, coverage);
                         }
                         return r_.ForEachItem(
                             value, path, "a list of projection names",
                             [&](const YAML::Node& item,
                                 const std::string& item_path) -> absl::Status {
                               DCS_ASSIGN_OR_RETURN(coverage.projections.emplace_back(),
                                                    r_.Word(item, item_path));
                               return absl::OkStatus();
                             });
                       });
}

absl::Status Parser::Ppo(const YAML::Node& node, PpoConfig& ppo) {
  const KeyTable<PpoConfig>& keys = PpoConfigKeys();
  return r_.ForEachKey(node, "ppo", keys.names(),
                       [&](const std::string& key, const YAML::Node& value,
                           const std::string& path) {
                         return ReadField(r_, keys[key], value, path, ppo);
                       });
}

void Parser::Document(const YAML::Node& root, RunSpec& spec, bool& schedule_key,
                      ConfigProblems& problems) {
  // Kept until every key is read: `schedule` and `stages` exclude each other.
  std::optional<YAML::Node> schedule_node;
  std::optional<YAML::Node> stages_node;
  auto read = [&](const std::string& key, const YAML::Node& value,
                  const std::string& path) -> absl::Status {
    if (const ConfigKey<RunSpec>& row = RunConfigKeys()[key]; row.has_field()) {
      return ReadField(r_, row, value, path, spec);
    } else if (key == "context") {
      return Context(value, path, spec);
    } else if (key == "training_range") {
      DCS_ASSIGN_OR_RETURN(const std::vector<double> range, r_.Numbers(value, path));
      if (range.size() != 2) {
        return r_.Error(
            path, value,
            absl::StrCat("must be a list of two numbers [lo, hi], got ", range.size()));
      }
      spec.range_lo = range[0];
      spec.range_hi = range[1];
    } else if (key == "pool") {
      return Pool(value, path, spec);
    } else if (key == "schedule") {
      schedule_node = value;
    } else if (key == "stages") {
      stages_node = value;
    } else if (key == "observe") {
      DCS_ASSIGN_OR_RETURN(const std::string mode, r_.Word(value, path));
      const std::optional<env::ObserveMode> observe = FindByName(env::kObserveModeNames, mode);
      if (!observe.has_value()) {
        return r_.Error(path, value,
                        absl::StrCat("must be ", ListNames(env::kObserveModeNames), ", got '",
                                     mode, "'"));
      }
      spec.observe = *observe;
    } else if (key == "evaluation") {
      return Evaluation(value, spec);
    } else if (key == "coverage") {
      return Coverage(value, spec);
    } else {
      return Ppo(value, spec.ppo);
    }
    return absl::OkStatus();
  };
  problems.Add(r_.ForEachKey(
      root, "", RunConfigKeys().names(),
      [&](const std::string& key, const YAML::Node& value, const std::string& path) {
        problems.Add(read(key, value, path));
        return absl::OkStatus();
      }));

  // The schedule: one for the whole run, or stages.
  if (schedule_node.has_value() && stages_node.has_value()) {
    problems.Add(r_.Error("stages", *stages_node,
                          "give either 'schedule' (one for the whole run) or 'stages', not both"));
    return;
  }
  schedule_key = schedule_node.has_value();
  if (schedule_node.has_value()) {
    absl::StatusOr<env::ScheduleConfig> schedule =
        ReadScheduleConfig(r_, *schedule_node, "schedule");
    if (schedule.ok()) {
      spec.stages.push_back({.steps = 0, .schedule = *std::move(schedule)});
    } else {
      problems.Add(schedule.status());
    }
  }
  if (stages_node.has_value()) problems.Add(Stages(*stages_node, spec));
}

}  // namespace

const KeyTable<RunSpec>& RunConfigKeys() {
  static const KeyTable<RunSpec>* const keys = [] {
    const RunSpec defaults;
    return new KeyTable<RunSpec>({
        {.name = "env",
         .meaning = "the environment",
         .field = &RunSpec::env,
         .type = OneOf(env::EnvironmentNames())},
        {.name = "seed",
         .meaning = "the run's seed: every random stream of the run derives from it",
         .field = &RunSpec::seed},
        {.name = "total_timesteps",
         .meaning = "environment steps to train for",
         .field = &RunSpec::total_timesteps,
         .bound = AtLeast(1)},
        {.name = "n_envs",
         .meaning = "training environments stepped together, each taking the pool rotated by "
                    "its index",
         .field = &RunSpec::n_envs,
         .bound = AtLeast(1)},
        {.name = "context",
         .meaning = "the other context features' values, by name, within their physical bounds",
         .type = "mapping of names to numbers",
         .default_value = "{} (their defaults)"},
        {.name = "feature", .meaning = "the varied context feature", .field = &RunSpec::feature},
        {.name = "training_range",
         .meaning = "[lo, hi] of the varied feature in training: lo < hi, within its physical "
                    "bounds",
         .type = "list of two numbers",
         .default_value = absl::StrCat("[", defaults.range_lo, ", ", defaults.range_hi, "]")},
        {.name = "pool",
         .meaning = "the values each episode starts from: size or values, not both",
         .type = "mapping",
         .default_value = absl::StrCat("{size: ", defaults.pool_size, "}")},
        {.name = "schedule",
         .meaning = "how the feature moves within each episode, for the whole run; not with "
                    "stages",
         .type = "schedule",
         .default_value = "none (static)"},
        {.name = "stages",
         .meaning = "schedules in turn, each for its steps; not with schedule",
         .type = "list of stages",
         .default_value = "none"},
        {.name = "observe",
         .meaning = "what the policy sees of the feature: nothing, its episode-initial value, "
                    "or its live value",
         .type = OneOf(NamesOf(env::kObserveModeNames)),
         .default_value = std::string(NameOf(env::kObserveModeNames, defaults.observe))},
        {.name = "evaluation",
         .meaning = "when the policy is evaluated, and on which values of the feature",
         .type = "mapping",
         .default_value = "required (its contexts)"},
        {.name = "ppo",
         .meaning = "PPO's settings",
         .type = "mapping",
         .default_value = "its keys' defaults"},
        {.name = "coverage",
         .meaning = "the coverage diagnostic, counted only if given",
         .type = "mapping",
         .default_value = "none (off)"},
    });
  }();
  return *keys;
}

std::vector<KeySection> RunConfigReference() {
  return {{"", Describe(RunConfigKeys())},
          {"pool", Describe(PoolKeys())},
          {"stages[i]", Describe(StageKeys())},
          {"evaluation", Describe(EvaluationKeys())},
          {"evaluation.contexts", Describe(EvaluationContextKeys())},
          {"ppo", Describe(PpoConfigKeys())},
          {"coverage", Describe(CoverageKeys())}};
}

absl::StatusOr<RunSpec> ParseRunSpecYaml(absl::string_view text, absl::string_view where) {
  YamlReader reader{std::string(where)};
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(text));
  return ReadRunSpec(reader, root);
}

absl::StatusOr<RunSpec> ReadRunSpec(YamlReader& reader, const YAML::Node& root) {
  ConfigProblems problems;
  std::optional<RunSpec> spec = ReadRunSpec(reader, root, problems);
  if (!spec.has_value()) return problems.ToStatus(reader.where());
  return *std::move(spec);
}

std::optional<RunSpec> ReadRunSpec(YamlReader& reader, const YAML::Node& root,
                                   ConfigProblems& problems) {
  RunSpec spec;
  bool schedule_key = false;
  const int reported = problems.reported();
  try {
    Parser(reader).Document(root, spec, schedule_key, problems);
  } catch (const YAML::Exception& e) {  // not expected: every access is checked first
    problems.Add(absl::InvalidArgumentError(absl::StrCat(reader.where(), ": line ",
                                                         e.mark.line + 1, ", column ",
                                                         e.mark.column + 1, ": ", e.msg)));
  }
  // A config read in part is not validated: its checks would see defaults for what was not.
  if (problems.reported() != reported) return std::nullopt;
  Validate(spec, reader.errors(), schedule_key, problems);
  if (problems.reported() != reported) return std::nullopt;
  return spec;
}

absl::Status ValidateRunSpec(const RunSpec& spec) {
  ConfigProblems problems;
  Validate(spec, ConfigErrors(), /*schedule_key=*/false, problems);
  return problems.ToStatus("");
}

}  // namespace dcs::run
