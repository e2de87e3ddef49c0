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
  for (size_t i = 0; i < spec.stages.size(); ++i) {
    const RunSpec::Stage& stage = spec.stages[i];
    if (!whole_run && stage.steps <= 0) {
      problems.Add(errors.At(absl::StrCat(ItemPath("stages", i), ".steps"),
                             absl::StrCat("must be at least 1 (0 only for a single stage, "
                                          "which then runs for the whole run), got ",
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
  } else if (spec.pool_size < 1 || spec.pool_size > kMaxPoolSize) {
    problems.Add(errors.At(
        "pool.size", absl::StrCat("must be in [1, ", kMaxPoolSize, "], got ", spec.pool_size)));
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
  if (spec.total_timesteps < 1) {
    problems.Add(errors.At("total_timesteps",
                           absl::StrCat("must be at least 1, got ", spec.total_timesteps)));
  }
  if (spec.n_envs < 1) {
    problems.Add(errors.At("n_envs", absl::StrCat("must be at least 1, got ", spec.n_envs)));
  }
  if (spec.eval_freq < 1) {
    problems.Add(
        errors.At("evaluation.freq", absl::StrCat("must be at least 1, got ", spec.eval_freq)));
  }
  if (spec.eval_episodes < 1) {
    problems.Add(errors.At("evaluation.episodes",
                           absl::StrCat("must be at least 1, got ", spec.eval_episodes)));
  }
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
      if (spec.coverage->window < 1) {
        problems.Add(errors.At("coverage.window",
                               absl::StrCat("must be at least 1, got ", spec.coverage->window)));
      }
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
  DCS_RETURN_IF_ERROR(r_.ForEachKey(
      node, path, {"size", "values"},
      [&](const std::string& key, const YAML::Node& value,
          const std::string& key_path) -> absl::Status {
        if (key == "size") {
          has_size = true;
          DCS_ASSIGN_OR_RETURN(spec.pool_size, r_.Int(value, key_path));
          return absl::OkStatus();
        }
        has_values = true;
        DCS_ASSIGN_OR_RETURN(spec.pool_values, r_.Numbers(value, key_path));
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
            stage_node, stage_path, {"steps", "schedule"},
            [&](const std::string& key, const YAML::Node& value,
                const std::string& path) -> absl::Status {
              if (key == "steps") {
                DCS_ASSIGN_OR_RETURN(stage.steps, r_.Int64(value, path));
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
  return r_.ForEachKey(
      node, "evaluation", {"freq", "episodes", "contexts"},
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
        if (key == "freq") {
          DCS_ASSIGN_OR_RETURN(spec.eval_freq, r_.Int64(value, path));
        } else if (key == "episodes") {
          DCS_ASSIGN_OR_RETURN(spec.eval_episodes, r_.Int(value, path));
        } else {
          return r_.ForEachKey(value, path, NamesOf(actor::kSplitNames),
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
  return r_.ForEachKey(node, "coverage", {"window", "projections"},
                       [&](const std::string& key, const YAML::Node& value,
                           const std::string& path) -> absl::Status {
                         if (key == "window") {
                           DCS_ASSIGN_OR_RETURN(coverage.window, r_.Int64(value, path));
                           return absl::OkStatus();
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
  const std::map<std::string, double*> numbers = {{"learning_rate", &ppo.learning_rate},
                                                  {"gamma", &ppo.gamma},
                                                  {"gae_lambda", &ppo.gae_lambda},
                                                  {"clip_range", &ppo.clip_range},
                                                  {"ent_coef", &ppo.ent_coef},
                                                  {"vf_coef", &ppo.vf_coef},
                                                  {"max_grad_norm", &ppo.max_grad_norm},
                                                  {"log_std_init", &ppo.log_std_init},
                                                  {"adam_eps", &ppo.adam_eps}};
  const std::map<std::string, int*> integers = {{"n_steps", &ppo.n_steps},
                                                {"batch_size", &ppo.batch_size},
                                                {"n_epochs", &ppo.n_epochs},
                                                {"cnn_features", &ppo.cnn_features}};
  return r_.ForEachKey(
      node, "ppo",
      {"learning_rate", "n_steps", "batch_size", "n_epochs", "gamma", "gae_lambda", "clip_range",
       "clip_range_vf", "normalize_advantage", "ent_coef", "vf_coef", "max_grad_norm", "target_kl",
       "pi_layers", "vf_layers", "log_std_init", "adam_eps", "cnn_features", "context_layers"},
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
        if (auto it = numbers.find(key); it != numbers.end()) {
          DCS_ASSIGN_OR_RETURN(*it->second, r_.Number(value, path));
        } else if (auto entry = integers.find(key); entry != integers.end()) {
          DCS_ASSIGN_OR_RETURN(*entry->second, r_.Int(value, path));
        } else if (key == "clip_range_vf" || key == "target_kl") {
          std::optional<double>& target = key == "target_kl" ? ppo.target_kl : ppo.clip_range_vf;
          if (value.IsNull()) {
            target.reset();
          } else {
            DCS_ASSIGN_OR_RETURN(target, r_.Number(value, path));
          }
        } else if (key == "normalize_advantage") {
          DCS_ASSIGN_OR_RETURN(ppo.normalize_advantage, r_.Bool(value, path));
        } else {
          std::vector<int>& target = key == "pi_layers"   ? ppo.pi_layers
                                     : key == "vf_layers" ? ppo.vf_layers
                                                          : ppo.context_layers;
          DCS_ASSIGN_OR_RETURN(target, r_.Ints(value, path));
        }
        return absl::OkStatus();
      });
}

void Parser::Document(const YAML::Node& root, RunSpec& spec, bool& schedule_key,
                      ConfigProblems& problems) {
  // Kept until every key is read: `schedule` and `stages` exclude each other.
  std::optional<YAML::Node> schedule_node;
  std::optional<YAML::Node> stages_node;
  auto read = [&](const std::string& key, const YAML::Node& value,
                  const std::string& path) -> absl::Status {
    if (key == "env") {
      DCS_ASSIGN_OR_RETURN(spec.env, r_.Word(value, path));
    } else if (key == "seed") {
      DCS_ASSIGN_OR_RETURN(spec.seed, r_.Uint64(value, path));
    } else if (key == "total_timesteps") {
      DCS_ASSIGN_OR_RETURN(spec.total_timesteps, r_.Int64(value, path));
    } else if (key == "n_envs") {
      DCS_ASSIGN_OR_RETURN(spec.n_envs, r_.Int(value, path));
    } else if (key == "context") {
      return Context(value, path, spec);
    } else if (key == "feature") {
      DCS_ASSIGN_OR_RETURN(spec.feature, r_.Word(value, path));
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
      root, "",
      {"env", "seed", "total_timesteps", "n_envs", "context", "feature", "training_range", "pool",
       "schedule", "stages", "observe", "evaluation", "ppo", "coverage"},
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
