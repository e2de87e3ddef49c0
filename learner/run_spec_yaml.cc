// Copyright 2026 The DCS Authors.
#include "learner/run_spec_yaml.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/strip.h"
#include "common/status_macros.h"
#include "coordinator/schedule_yaml.h"
#include "env/context_feature.h"
#include "env/env_registry.h"
#include "env/schedule_config.h"
#include "learner/ppo_config.h"

namespace dcs::learner {
namespace {

constexpr int kMaxPoolSize = 10'000;                     // env::ContextPool::OfSize's limit
constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53

// Formats errors as "<where>: <path>: line <n>: <message>", leaving out what is unknown: the
// text's name and the lines of the fields (both known only when parsing). Also names stages.
class Reporter {
 public:
  Reporter() = default;
  Reporter(std::string where, const std::map<std::string, int>* lines, bool schedule_key)
      : where_(std::move(where)), lines_(lines), schedule_key_(schedule_key) {}

  absl::Status Error(absl::string_view path, absl::string_view message) const {
    std::string text;
    if (!where_.empty()) absl::StrAppend(&text, where_, ": ");
    absl::StrAppend(&text, path, ": ");
    if (lines_ != nullptr) {
      if (auto it = lines_->find(std::string(path)); it != lines_->end()) {
        absl::StrAppend(&text, "line ", it->second, ": ");
      }
    }
    absl::StrAppend(&text, message);
    return absl::InvalidArgumentError(text);
  }

  // The YAML path of stage `index`'s schedule: `schedule` when the config gave one schedule.
  std::string SchedulePath(int index) const {
    return schedule_key_ ? std::string("schedule") : absl::StrCat("stages[", index, "].schedule");
  }

 private:
  std::string where_;
  const std::map<std::string, int>* lines_ = nullptr;
  bool schedule_key_ = false;
};

std::string Item(absl::string_view path, size_t index) {
  return absl::StrCat(path, "[", index, "]");
}

// ---------------------------------------------------------------------------------------------
// Validation.

// ValidatePpoConfig's "ppo: <field> must be ..." as the field's path and the rule.
absl::Status PpoError(const Reporter& reporter, const absl::Status& status) {
  absl::string_view message = status.message();
  if (absl::ConsumePrefix(&message, "ppo: ")) {
    const size_t end = message.find(" must be ");
    if (end != absl::string_view::npos &&
        message.substr(0, end).find(' ') == absl::string_view::npos) {
      return reporter.Error(absl::StrCat("ppo.", message.substr(0, end)), message.substr(end + 1));
    }
  }
  return reporter.Error("ppo", message);
}

absl::Status CheckWithEnvironment(const RunSpec& spec, const env::ContextSpace& space,
                                  absl::Status (*validate_context)(std::span<const double>),
                                  const Reporter& reporter) {
  // The varied feature and its training range.
  absl::StatusOr<int> feature = space.IndexOf(spec.feature);
  if (!feature.ok()) return reporter.Error("feature", feature.status().message());
  const double lo = spec.range_lo;
  const double hi = spec.range_hi;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    return reporter.Error(
        "training_range",
        absl::StrCat("must be [lo, hi] with lo < hi, both finite, got [", lo, ", ", hi, "]"));
  }
  if (absl::Status s = space.Validate(*feature, lo); !s.ok()) {
    return reporter.Error("training_range[0]", s.message());
  }
  if (absl::Status s = space.Validate(*feature, hi); !s.ok()) {
    return reporter.Error("training_range[1]", s.message());
  }

  // The other features' values.
  std::vector<double> values = space.Defaults();
  for (const auto& [name, value] : spec.context) {
    const std::string path = absl::StrCat("context.", name);
    absl::StatusOr<int> index = space.IndexOf(name);
    if (!index.ok()) return reporter.Error(path, index.status().message());
    if (*index == *feature) {
      return reporter.Error(path, absl::StrCat("'", name,
                                               "' is the varied feature: its values come from "
                                               "training_range, pool and evaluation.contexts"));
    }
    if (absl::Status s = space.Validate(*index, value); !s.ok()) {
      return reporter.Error(path, s.message());
    }
    values[*index] = value;
  }
  // The full context, at every value the varied feature takes in training and evaluation.
  auto check_full = [&](double value, absl::string_view path) -> absl::Status {
    values[*feature] = value;
    if (absl::Status s = validate_context(values); !s.ok()) {
      return reporter.Error(path, absl::StrCat("the context is invalid with ", spec.feature, " = ",
                                               value, ": ", s.message()));
    }
    return absl::OkStatus();
  };
  DCS_RETURN_IF_ERROR(check_full(lo, "context"));
  DCS_RETURN_IF_ERROR(check_full(hi, "context"));

  // The pool.
  if (!spec.pool_values.empty()) {
    for (size_t i = 0; i < spec.pool_values.size(); ++i) {
      const double value = spec.pool_values[i];
      if (!(value >= lo && value <= hi)) {
        return reporter.Error(
            Item("pool.values", i),
            absl::StrCat("must be within training_range [", lo, ", ", hi, "], got ", value));
      }
      DCS_RETURN_IF_ERROR(check_full(value, Item("pool.values", i)));
    }
  } else if (spec.pool_size < 1 || spec.pool_size > kMaxPoolSize) {
    return reporter.Error("pool.size",
                          absl::StrCat("must be in [1, ", kMaxPoolSize, "], got ", spec.pool_size));
  }

  // The stages.
  const bool whole_run = spec.stages.size() == 1 && spec.stages[0].steps == 0;
  int64_t start = 0;
  for (size_t i = 0; i < spec.stages.size(); ++i) {
    const RunSpec::Stage& stage = spec.stages[i];
    if (!whole_run && stage.steps <= 0) {
      return reporter.Error(absl::StrCat("stages[", i, "].steps"),
                            absl::StrCat("must be at least 1 (0 only for a single stage, which "
                                         "then runs for the whole run), got ",
                                         stage.steps));
    }
    if (i > 0 && start >= spec.total_timesteps) {
      return reporter.Error(absl::StrCat("stages[", i, "]"),
                            absl::StrCat("starts at step ", start, ", not before total_timesteps (",
                                         spec.total_timesteps, "): it would never run"));
    }
    start += stage.steps;
    absl::StatusOr<env::ScheduleSpec> schedule =
        env::ParseScheduleSpec(stage.schedule, lo, hi, static_cast<uint32_t>(spec.seed));
    if (!schedule.ok()) {
      return reporter.Error(reporter.SchedulePath(static_cast<int>(i)),
                            schedule.status().message());
    }
  }

  // The evaluation contexts: physical bounds only (OOD values lie outside the training range).
  const std::pair<const char*, const std::vector<double>*> splits[] = {
      {"evaluation.contexts.id", &spec.eval_id},
      {"evaluation.contexts.ood_low", &spec.eval_ood_low},
      {"evaluation.contexts.ood_high", &spec.eval_ood_high}};
  for (const auto& [split, contexts] : splits) {
    for (size_t i = 0; i < contexts->size(); ++i) {
      const double value = (*contexts)[i];
      if (absl::Status s = space.Validate(*feature, value); !s.ok()) {
        return reporter.Error(Item(split, i), s.message());
      }
      DCS_RETURN_IF_ERROR(check_full(value, Item(split, i)));
    }
  }
  return absl::OkStatus();
}

absl::Status Validate(const RunSpec& spec, const Reporter& reporter) {
  if (spec.total_timesteps < 1) {
    return reporter.Error("total_timesteps",
                          absl::StrCat("must be at least 1, got ", spec.total_timesteps));
  }
  if (spec.n_envs < 1) {
    return reporter.Error("n_envs", absl::StrCat("must be at least 1, got ", spec.n_envs));
  }
  if (spec.observe != "none" && spec.observe != "initial" && spec.observe != "live") {
    return reporter.Error("observe",
                          absl::StrCat("must be none, initial or live, got '", spec.observe, "'"));
  }
  if (spec.eval_freq < 1) {
    return reporter.Error("evaluation.freq",
                          absl::StrCat("must be at least 1, got ", spec.eval_freq));
  }
  if (spec.eval_episodes < 1) {
    return reporter.Error("evaluation.episodes",
                          absl::StrCat("must be at least 1, got ", spec.eval_episodes));
  }
  if (spec.eval_id.empty() && spec.eval_ood_low.empty() && spec.eval_ood_high.empty()) {
    return reporter.Error("evaluation.contexts",
                          "needs at least one evaluation context (in id, ood_low or ood_high)");
  }
  const std::vector<std::string> environments = env::EnvironmentNames();
  if (std::find(environments.begin(), environments.end(), spec.env) == environments.end()) {
    return reporter.Error("env", absl::StrCat("unknown environment '", spec.env, "' (known: ",
                                              absl::StrJoin(environments, ", "), ")"));
  }
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
    return CheckWithEnvironment(spec, Env::Features(), &Env::ValidateContext, reporter);
  }));
  if (absl::Status s = ValidatePpoConfig(spec.ppo, spec.n_envs); !s.ok()) {
    return PpoError(reporter, s);
  }
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------------------------
// Parsing.

// Reads one document's nodes into a RunSpec, remembering the line of every field it reads.
class Parser {
 public:
  explicit Parser(absl::string_view where) : where_(where) {}

  const std::map<std::string, int>& lines() const { return lines_; }

  // "<where>: <path>: line <n>: <message>"; no path at the top level.
  absl::Status Error(absl::string_view path, const YAML::Node& node,
                     absl::string_view message) const {
    const YAML::Mark mark = node.Mark();
    return absl::InvalidArgumentError(
        absl::StrCat(where_, ": ", path, path.empty() ? "" : ": ",
                     mark.is_null() ? "" : absl::StrCat("line ", mark.line + 1, ": "), message));
  }

  // Records where `path` is, for errors found later.
  void Note(const std::string& path, const YAML::Node& node) {
    if (!node.Mark().is_null()) lines_[path] = node.Mark().line + 1;
  }

  // `node` must be a mapping whose keys are among `allowed`, each once; `path` names it ("" at
  // the top level). Calls `read(key, value, key_path)` for each entry, in order.
  template <typename Read>
  absl::Status ForEachKey(const YAML::Node& node, absl::string_view path,
                          std::initializer_list<absl::string_view> allowed, Read&& read) {
    const std::string name = path.empty() ? "the config" : std::string(path);
    if (!node.IsMap()) {
      return Error(
          path, node,
          absl::StrCat(name, " must be a mapping with keys ", absl::StrJoin(allowed, ", ")));
    }
    std::set<std::string> seen;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) {
        return Error(path, entry.first, "a key must be a name, not a list or mapping");
      }
      const std::string key = entry.first.Scalar();
      const std::string key_path = path.empty() ? key : absl::StrCat(path, ".", key);
      bool known = false;
      for (absl::string_view a : allowed) known = known || a == key;
      if (!known) {
        return Error(
            key_path, entry.first,
            absl::StrCat("unknown key '", key, "' ",
                         path.empty() ? std::string("at the top level") : absl::StrCat("in ", path),
                         " (allowed: ", absl::StrJoin(allowed, ", "), ")"));
      }
      if (!seen.insert(key).second) {
        return Error(key_path, entry.first, absl::StrCat("key '", key, "' given twice"));
      }
      Note(key_path, entry.second);
      DCS_RETURN_IF_ERROR(read(key, entry.second, key_path));
    }
    return absl::OkStatus();
  }

  // OK if `node` is a plain (unquoted) scalar, else an error saying the field must be `what`.
  absl::Status PlainScalar(const YAML::Node& node, absl::string_view path,
                           absl::string_view what) const {
    if (node.IsNull()) return Error(path, node, absl::StrCat("must be ", what, ", got null"));
    if (!node.IsScalar()) {
      return Error(
          path, node,
          absl::StrCat("must be ", what, ", got a ", node.IsSequence() ? "list" : "mapping"));
    }
    if (node.Tag() != "?" && node.Tag() != "tag:yaml.org,2002:int" &&
        node.Tag() != "tag:yaml.org,2002:float" && node.Tag() != "tag:yaml.org,2002:bool") {
      return Error(path, node,
                   absl::StrCat("must be ", what, ", got the string \"", node.Scalar(), "\""));
    }
    return absl::OkStatus();
  }

  absl::StatusOr<double> Number(const YAML::Node& node, absl::string_view path) const {
    DCS_RETURN_IF_ERROR(PlainScalar(node, path, "a number"));
    const std::string& text = node.Scalar();
    std::optional<double> value = ParseDouble(text);
    if (!value.has_value()) {
      return Error(path, node, absl::StrCat("must be a number, got '", text, "'"));
    }
    if (!std::isfinite(*value)) {
      return Error(path, node, absl::StrCat("must be a finite number, got '", text, "'"));
    }
    return *value;
  }

  // An integer of type T: digits, or a number with an integral value ("3e6").
  template <typename T>
  absl::StatusOr<T> Integer(const YAML::Node& node, absl::string_view path) const {
    const std::string what = std::is_signed_v<T> ? "an integer" : "a non-negative integer";
    DCS_RETURN_IF_ERROR(PlainScalar(node, path, what));
    const std::string& text = node.Scalar();
    absl::string_view digits = text;
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    T value{};
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error == std::errc() && end == digits.data() + digits.size()) return value;
    const std::string range = absl::StrCat(" in [", std::numeric_limits<T>::min(), ", ",
                                           std::numeric_limits<T>::max(), "]");
    if (error == std::errc::result_out_of_range) {
      return Error(path, node, absl::StrCat("must be ", what, range, ", got ", text));
    }
    std::optional<double> number = ParseDouble(text);
    if (!number.has_value() || !std::isfinite(*number) || *number != std::trunc(*number)) {
      return Error(path, node, absl::StrCat("must be ", what, ", got '", text, "'"));
    }
    if (std::abs(*number) > kMaxExactInteger ||
        *number < static_cast<double>(std::numeric_limits<T>::min()) ||
        *number > static_cast<double>(std::numeric_limits<T>::max())) {
      return Error(path, node, absl::StrCat("must be ", what, range, ", got ", text));
    }
    return static_cast<T>(*number);
  }

  absl::StatusOr<bool> Bool(const YAML::Node& node, absl::string_view path) const {
    DCS_RETURN_IF_ERROR(PlainScalar(node, path, "true or false"));
    const std::string& text = node.Scalar();
    bool value = false;
    if (!YAML::convert<bool>::decode(node, value)) {
      return Error(path, node, absl::StrCat("must be true or false, got '", text, "'"));
    }
    return value;
  }

  absl::StatusOr<std::string> Word(const YAML::Node& node, absl::string_view path) const {
    if (node.IsNull() || !node.IsScalar()) {
      return Error(
          path, node,
          node.IsNull() ? "must be a name, got null" : "must be a name, not a list or mapping");
    }
    return node.Scalar();
  }

  // A list of numbers; each item's line is noted as `path[i]`.
  absl::StatusOr<std::vector<double>> Numbers(const YAML::Node& node, const std::string& path) {
    if (!node.IsSequence()) return Error(path, node, "must be a list of numbers");
    std::vector<double> values;
    for (size_t i = 0; i < node.size(); ++i) {
      Note(Item(path, i), node[i]);
      DCS_ASSIGN_OR_RETURN(double value, Number(node[i], Item(path, i)));
      values.push_back(value);
    }
    return values;
  }

  absl::StatusOr<std::vector<int>> Integers(const YAML::Node& node, const std::string& path) {
    if (!node.IsSequence()) return Error(path, node, "must be a list of integers");
    std::vector<int> values;
    for (size_t i = 0; i < node.size(); ++i) {
      Note(Item(path, i), node[i]);
      DCS_ASSIGN_OR_RETURN(int value, Integer<int>(node[i], Item(path, i)));
      values.push_back(value);
    }
    return values;
  }

  absl::StatusOr<env::ScheduleConfig> Schedule(const YAML::Node& node, const std::string& path) {
    return coordinator::ScheduleConfigFromYaml(node, absl::StrCat(where_, ": ", path));
  }

  absl::Status Document(const YAML::Node& root, RunSpec& spec, bool& schedule_key);

 private:
  static std::optional<double> ParseDouble(absl::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
  }

  absl::Status Evaluation(const YAML::Node& node, RunSpec& spec);
  absl::Status EvaluationContexts(const YAML::Node& node, const std::string& path, RunSpec& spec);
  absl::Status Ppo(const YAML::Node& node, PpoConfig& ppo);

  std::string where_;
  std::map<std::string, int> lines_;
};

absl::Status Parser::Evaluation(const YAML::Node& node, RunSpec& spec) {
  return ForEachKey(node, "evaluation", {"freq", "episodes", "contexts"},
                    [&](const std::string& key, const YAML::Node& value,
                        const std::string& path) -> absl::Status {
                      if (key == "freq") {
                        DCS_ASSIGN_OR_RETURN(spec.eval_freq, Integer<int64_t>(value, path));
                      } else if (key == "episodes") {
                        DCS_ASSIGN_OR_RETURN(spec.eval_episodes, Integer<int>(value, path));
                      } else {
                        return EvaluationContexts(value, path, spec);
                      }
                      return absl::OkStatus();
                    });
}

absl::Status Parser::EvaluationContexts(const YAML::Node& node, const std::string& path,
                                        RunSpec& spec) {
  return ForEachKey(node, path, {"id", "ood_low", "ood_high"},
                    [&](const std::string& split, const YAML::Node& value,
                        const std::string& split_path) -> absl::Status {
                      std::vector<double>* target = &spec.eval_ood_high;
                      if (split == "id") target = &spec.eval_id;
                      if (split == "ood_low") target = &spec.eval_ood_low;
                      DCS_ASSIGN_OR_RETURN(*target, Numbers(value, split_path));
                      return absl::OkStatus();
                    });
}

absl::Status Parser::Ppo(const YAML::Node& node, PpoConfig& ppo) {
  return ForEachKey(
      node, "ppo",
      {"learning_rate", "n_steps", "batch_size", "n_epochs", "gamma", "gae_lambda", "clip_range",
       "clip_range_vf", "normalize_advantage", "ent_coef", "vf_coef", "max_grad_norm", "target_kl",
       "pi_layers", "vf_layers", "log_std_init", "adam_eps", "cnn_features"},
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
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
        if (auto it = numbers.find(key); it != numbers.end()) {
          DCS_ASSIGN_OR_RETURN(*it->second, Number(value, path));
        } else if (auto entry = integers.find(key); entry != integers.end()) {
          DCS_ASSIGN_OR_RETURN(*entry->second, Integer<int>(value, path));
        } else if (key == "clip_range_vf" || key == "target_kl") {
          std::optional<double>& target = key == "target_kl" ? ppo.target_kl : ppo.clip_range_vf;
          if (value.IsNull()) {
            target.reset();
          } else {
            DCS_ASSIGN_OR_RETURN(target, Number(value, path));
          }
        } else if (key == "normalize_advantage") {
          DCS_ASSIGN_OR_RETURN(ppo.normalize_advantage, Bool(value, path));
        } else {
          std::vector<int>& target = key == "pi_layers" ? ppo.pi_layers : ppo.vf_layers;
          DCS_ASSIGN_OR_RETURN(target, Integers(value, path));
        }
        return absl::OkStatus();
      });
}

absl::Status Parser::Document(const YAML::Node& root, RunSpec& spec, bool& schedule_key) {
  // Kept until every key is read: `schedule` and `stages` exclude each other.
  std::optional<YAML::Node> schedule_node;
  std::optional<YAML::Node> stages_node;
  // (Statuses held in variables: DCS_RETURN_IF_ERROR does not nest.)
  const absl::Status keys = ForEachKey(
      root, "",
      {"env", "seed", "total_timesteps", "n_envs", "context", "feature", "training_range", "pool",
       "schedule", "stages", "observe", "evaluation", "ppo"},
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
        if (key == "env") {
          DCS_ASSIGN_OR_RETURN(spec.env, Word(value, path));
        } else if (key == "seed") {
          DCS_ASSIGN_OR_RETURN(spec.seed, Integer<uint64_t>(value, path));
        } else if (key == "total_timesteps") {
          DCS_ASSIGN_OR_RETURN(spec.total_timesteps, Integer<int64_t>(value, path));
        } else if (key == "n_envs") {
          DCS_ASSIGN_OR_RETURN(spec.n_envs, Integer<int>(value, path));
        } else if (key == "context") {
          if (!value.IsMap()) {
            return Error(path, value, "must be a mapping of feature names to values");
          }
          for (const auto& entry : value) {
            if (!entry.first.IsScalar()) {
              return Error(path, entry.first, "a key must be a feature name");
            }
            const std::string name = entry.first.Scalar();
            const std::string feature_path = absl::StrCat(path, ".", name);
            if (spec.context.contains(name)) {
              return Error(feature_path, entry.first, absl::StrCat("key '", name, "' given twice"));
            }
            Note(feature_path, entry.second);
            DCS_ASSIGN_OR_RETURN(spec.context[name], Number(entry.second, feature_path));
          }
        } else if (key == "feature") {
          DCS_ASSIGN_OR_RETURN(spec.feature, Word(value, path));
        } else if (key == "training_range") {
          DCS_ASSIGN_OR_RETURN(std::vector<double> range, Numbers(value, path));
          if (range.size() != 2) {
            return Error(
                path, value,
                absl::StrCat("must be a list of two numbers [lo, hi], got ", range.size()));
          }
          spec.range_lo = range[0];
          spec.range_hi = range[1];
        } else if (key == "pool") {
          bool has_size = false;
          bool has_values = false;
          const absl::Status pool = ForEachKey(
              value, path, {"size", "values"},
              [&](const std::string& pool_key, const YAML::Node& pool_value,
                  const std::string& pool_path) -> absl::Status {
                if (pool_key == "size") {
                  has_size = true;
                  DCS_ASSIGN_OR_RETURN(spec.pool_size, Integer<int>(pool_value, pool_path));
                } else {
                  has_values = true;
                  DCS_ASSIGN_OR_RETURN(spec.pool_values, Numbers(pool_value, pool_path));
                  if (spec.pool_values.empty()) {
                    return Error(pool_path, pool_value, "must list at least one value");
                  }
                }
                return absl::OkStatus();
              });
          if (!pool.ok()) return pool;
          if (has_size == has_values) {
            return Error(path, value, "must give exactly one of size and values");
          }
        } else if (key == "schedule") {
          schedule_node = value;
        } else if (key == "stages") {
          stages_node = value;
        } else if (key == "observe") {
          DCS_ASSIGN_OR_RETURN(spec.observe, Word(value, path));
        } else if (key == "evaluation") {
          DCS_RETURN_IF_ERROR(Evaluation(value, spec));
        } else {
          DCS_RETURN_IF_ERROR(Ppo(value, spec.ppo));
        }
        return absl::OkStatus();
      });
  if (!keys.ok()) return keys;

  // The schedule: one for the whole run, or stages.
  if (schedule_node.has_value() && stages_node.has_value()) {
    return Error("stages", *stages_node,
                 "give either 'schedule' (one for the whole run) or 'stages', not both");
  }
  schedule_key = schedule_node.has_value();
  if (schedule_node.has_value()) {
    DCS_ASSIGN_OR_RETURN(env::ScheduleConfig schedule, Schedule(*schedule_node, "schedule"));
    spec.stages.push_back({.steps = 0, .schedule = std::move(schedule)});
  }
  if (stages_node.has_value()) {
    if (!stages_node->IsSequence()) {
      return Error("stages", *stages_node, "must be a list of {steps: N, schedule: {family: ...}}");
    }
    for (size_t i = 0; i < stages_node->size(); ++i) {
      const YAML::Node stage_node = (*stages_node)[i];
      const std::string stage_path = Item("stages", i);
      Note(stage_path, stage_node);
      RunSpec::Stage stage;
      bool has_schedule = false;
      DCS_RETURN_IF_ERROR(
          ForEachKey(stage_node, stage_path, {"steps", "schedule"},
                     [&](const std::string& key, const YAML::Node& value,
                         const std::string& path) -> absl::Status {
                       if (key == "steps") {
                         DCS_ASSIGN_OR_RETURN(stage.steps, Integer<int64_t>(value, path));
                       } else {
                         has_schedule = true;
                         DCS_ASSIGN_OR_RETURN(stage.schedule, Schedule(value, path));
                       }
                       return absl::OkStatus();
                     }));
      if (!has_schedule) {
        return Error(stage_path, stage_node,
                     "a stage needs a schedule (e.g. {family: constant} for none)");
      }
      spec.stages.push_back(std::move(stage));
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<RunSpec> ParseRunSpecYaml(absl::string_view text, absl::string_view where) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": line ", e.mark.line + 1, ", column ",
                                                   e.mark.column + 1, ": ", e.msg));
  }
  RunSpec spec;
  Parser parser(where);
  bool schedule_key = false;
  try {
    DCS_RETURN_IF_ERROR(parser.Document(root, spec, schedule_key));
  } catch (const YAML::Exception& e) {  // not expected: every access is checked first
    return absl::InvalidArgumentError(absl::StrCat(where, ": line ", e.mark.line + 1, ", column ",
                                                   e.mark.column + 1, ": ", e.msg));
  }
  DCS_RETURN_IF_ERROR(Validate(spec, Reporter(std::string(where), &parser.lines(), schedule_key)));
  return spec;
}

absl::Status ValidateRunSpec(const RunSpec& spec) { return Validate(spec, Reporter()); }

}  // namespace dcs::learner
