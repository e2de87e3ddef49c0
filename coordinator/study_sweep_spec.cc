// Copyright 2026 The DCS Authors.
#include "coordinator/study_sweep_spec.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "coordinator/sampler.h"
#include "run/search_space_yaml.h"
#include "run/study_config.h"
#include "run/sweep_spec_yaml.h"
#include "run/yaml_reader.h"

namespace dcs::coordinator {
namespace {

// Samples of the space whose run configs are checked before the study is accepted, so that a
// space that writes a wrong key or value is refused at submission, not trial by trial.
constexpr int kCheckedSamples = 32;

// A name of `names` at `path`, as the run config reads its enumerations.
template <typename Enum, size_t N>
absl::StatusOr<Enum> ReadName(run::YamlReader& reader, const YAML::Node& node,
                              const std::string& path, const EnumName<Enum> (&names)[N]) {
  DCS_ASSIGN_OR_RETURN(const std::string word, reader.Word(node, path));
  if (std::optional<Enum> value = FindByName(names, word)) return *value;
  return reader.Error(path, node, absl::StrCat("must be ", ListNames(names), ", got '", word, "'"));
}

absl::Status ReadTpe(run::YamlReader& reader, const YAML::Node& node, const std::string& path,
                     TpeOptions& tpe) {
  constexpr absl::string_view kKeys[] = {"startup_trials", "ei_candidates", "multivariate", "group",
                                         "constant_liar"};
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      node, path, kKeys,
      [&](const std::string& key, const YAML::Node& value,
          const std::string& key_path) -> absl::Status {
        if (key == "startup_trials") {
          DCS_ASSIGN_OR_RETURN(tpe.startup_trials, reader.Int(value, key_path));
        } else if (key == "ei_candidates") {
          DCS_ASSIGN_OR_RETURN(tpe.ei_candidates, reader.Int(value, key_path));
        } else if (key == "multivariate") {
          DCS_ASSIGN_OR_RETURN(tpe.parzen.multivariate, reader.Bool(value, key_path));
        } else if (key == "group") {
          DCS_ASSIGN_OR_RETURN(tpe.group, reader.Bool(value, key_path));
        } else {
          DCS_ASSIGN_OR_RETURN(tpe.constant_liar, reader.Bool(value, key_path));
        }
        return absl::OkStatus();
      }));
  if (absl::Status status = ValidateTpeOptions(tpe); !status.ok()) {
    return reader.Error(path, node, status.message());
  }
  return absl::OkStatus();
}

absl::Status ReadPruner(run::YamlReader& reader, const YAML::Node& node, const std::string& path,
                        PrunerOptions& pruner) {
  constexpr absl::string_view kKeys[] = {
      "kind",           "percentile",       "startup_trials",
      "warmup_steps",   "interval_steps",   "min_trials",
      "min_resource",   "reduction_factor", "min_early_stopping_rate",
      "bootstrap_count"};
  MedianPrunerOptions& median = pruner.median;
  SuccessiveHalvingOptions& halving = pruner.halving;
  bool has_kind = false;
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      node, path, kKeys,
      [&](const std::string& key, const YAML::Node& value,
          const std::string& key_path) -> absl::Status {
        if (key == "kind") {
          has_kind = true;
          DCS_ASSIGN_OR_RETURN(pruner.kind, ReadName(reader, value, key_path, kPrunerKindNames));
        } else if (key == "percentile") {
          DCS_ASSIGN_OR_RETURN(median.percentile, reader.Number(value, key_path));
        } else if (key == "startup_trials") {
          DCS_ASSIGN_OR_RETURN(median.startup_trials, reader.Int(value, key_path));
        } else if (key == "warmup_steps") {
          DCS_ASSIGN_OR_RETURN(median.warmup_steps, reader.Int64(value, key_path));
        } else if (key == "interval_steps") {
          DCS_ASSIGN_OR_RETURN(median.interval_steps, reader.Int64(value, key_path));
        } else if (key == "min_trials") {
          DCS_ASSIGN_OR_RETURN(median.min_trials, reader.Int(value, key_path));
        } else if (key == "min_resource") {
          DCS_ASSIGN_OR_RETURN(halving.min_resource, reader.Int64(value, key_path));
        } else if (key == "reduction_factor") {
          DCS_ASSIGN_OR_RETURN(halving.reduction_factor, reader.Int(value, key_path));
        } else if (key == "min_early_stopping_rate") {
          DCS_ASSIGN_OR_RETURN(halving.min_early_stopping_rate, reader.Int(value, key_path));
        } else {
          DCS_ASSIGN_OR_RETURN(halving.bootstrap_count, reader.Int(value, key_path));
        }
        return absl::OkStatus();
      }));
  if (!has_kind)
    return reader.Error(path, node, "missing 'kind' (none, median, successive_halving)");
  if (absl::Status status = ValidatePrunerOptions(pruner); !status.ok()) {
    return reader.Error(path, node, status.message());
  }
  return absl::OkStatus();
}

// retrain: {top_k: K, seeds: N or [...]}: N seeds after the largest of `search_seeds`.
absl::Status ReadRetrain(run::YamlReader& reader, const YAML::Node& node, const std::string& path,
                         const std::vector<uint64_t>& search_seeds, StudySweepSpec& spec) {
  constexpr absl::string_view kKeys[] = {"top_k", "seeds"};
  bool has_seeds = false;
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      node, path, kKeys,
      [&](const std::string& key, const YAML::Node& value,
          const std::string& key_path) -> absl::Status {
        if (key == "top_k") {
          DCS_ASSIGN_OR_RETURN(spec.retrain_top_k, reader.Int(value, key_path));
          if (spec.retrain_top_k < 1) return reader.Error(key_path, value, "must be at least 1");
          return absl::OkStatus();
        }
        has_seeds = true;
        if (value.IsScalar()) {
          DCS_ASSIGN_OR_RETURN(const int count, reader.Int(value, key_path));
          if (count < 1) return reader.Error(key_path, value, "must be at least 1");
          const uint64_t first = *std::max_element(search_seeds.begin(), search_seeds.end()) + 1;
          for (int i = 0; i < count; ++i) spec.retrain_seeds.push_back(first + i);
          return absl::OkStatus();
        }
        return reader.ForEachItem(
            value, key_path, "a number of seeds N or a list of seeds",
            [&](const YAML::Node& item, const std::string& item_path) -> absl::Status {
              DCS_ASSIGN_OR_RETURN(const uint64_t seed, reader.Uint64(item, item_path));
              if (std::find(search_seeds.begin(), search_seeds.end(), seed) != search_seeds.end()) {
                return reader.Error(item_path, item,
                                    absl::StrCat("seed ", seed,
                                                 " is one of the search's: a "
                                                 "retrain uses new seeds"));
              }
              if (std::find(spec.retrain_seeds.begin(), spec.retrain_seeds.end(), seed) !=
                  spec.retrain_seeds.end()) {
                return reader.Error(item_path, item, absl::StrCat("seed ", seed, " given twice"));
              }
              spec.retrain_seeds.push_back(seed);
              return absl::OkStatus();
            });
      }));
  if (spec.retrain_top_k == 0 || !has_seeds) {
    return reader.Error(path, node, "a retrain gives top_k and seeds");
  }
  return absl::OkStatus();
}

// A run config of the space's samples fails to validate: the first such, named.
absl::Status CheckSamples(const StudySweepSpec& spec, const std::string& where) {
  Random random(StreamSeed(spec.study.seed, "space check"));
  for (int i = 0; i < kCheckedSamples; ++i) {
    const run::ParameterValues values = RandomValues(spec.space, random);
    absl::StatusOr<run::SeededRuns> config =
        run::TrialRunConfig(spec.sweep.trials.front().config, where, spec.space, values);
    if (!config.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat(where,
                       ": study.space: a sample of the space makes a run config that does "
                       "not validate: ",
                       config.status().message()));
    }
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<StudySweepSpec> ParseStudySweepYaml(absl::string_view text,
                                                   absl::string_view where) {
  run::YamlReader reader{std::string(where)};
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(text));
  DCS_ASSIGN_OR_RETURN(run::SweepSpec sweep, run::ReadSweepSpec(reader, root));
  return ReadStudySweep(reader, root, std::move(sweep));
}

absl::StatusOr<StudySweepSpec> ReadStudySweep(run::YamlReader& reader, const YAML::Node& root,
                                              run::SweepSpec sweep) {
  StudySweepSpec spec{.sweep = std::move(sweep)};
  const std::string& where = reader.where();
  if (!spec.sweep.study) {
    return absl::InvalidArgumentError(
        absl::StrCat(where, ": study: missing: a study sweep has a study block"));
  }
  if (spec.sweep.trials.size() != 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        where,
        ": conditions: a study searches one condition in one observation mode; the spec "
        "has ",
        spec.sweep.trials.size(), " (conditions times modes)"));
  }
  const YAML::Node block = root["study"];
  constexpr absl::string_view kKeys[] = {"trials",    "parallel", "sampler", "seed", "tpe",
                                         "objective", "pruner",   "retrain", "space"};
  spec.study.direction = Direction::kMaximize;
  bool has_trials = false;
  std::optional<YAML::Node> space;
  std::optional<std::pair<YAML::Node, std::string>> retrain;
  DCS_RETURN_IF_ERROR(reader.ForEachKey(
      block, "study", kKeys,
      [&](const std::string& key, const YAML::Node& value,
          const std::string& path) -> absl::Status {
        if (key == "trials") {
          has_trials = true;
          DCS_ASSIGN_OR_RETURN(spec.trials, reader.Int(value, path));
          if (spec.trials < 1) return reader.Error(path, value, "must be at least 1");
        } else if (key == "parallel") {
          DCS_ASSIGN_OR_RETURN(spec.parallel, reader.Int(value, path));
          if (spec.parallel < 1) return reader.Error(path, value, "must be at least 1");
        } else if (key == "sampler") {
          DCS_ASSIGN_OR_RETURN(spec.study.sampler,
                               ReadName(reader, value, path, kSamplerKindNames));
        } else if (key == "seed") {
          DCS_ASSIGN_OR_RETURN(spec.study.seed, reader.Uint64(value, path));
        } else if (key == "tpe") {
          return ReadTpe(reader, value, path, spec.study.tpe);
        } else if (key == "objective") {
          DCS_ASSIGN_OR_RETURN(spec.objective, ReadName(reader, value, path, kStudyObjectiveNames));
        } else if (key == "pruner") {
          return ReadPruner(reader, value, path, spec.study.pruner);
        } else if (key == "retrain") {
          retrain.emplace(value, path);  // read once the search's seeds are known
        } else {
          space.emplace(value);
        }
        return absl::OkStatus();
      }));
  if (!has_trials) {
    return reader.Error("study", block, "missing 'trials': how many trials the study asks for");
  }
  if (!space.has_value()) {
    return reader.Error("study", block, "missing 'space': the parameters the study searches");
  }
  if (retrain.has_value()) {
    DCS_RETURN_IF_ERROR(
        ReadRetrain(reader, retrain->first, retrain->second, spec.sweep.seeds, spec));
  }
  DCS_ASSIGN_OR_RETURN(spec.space, run::ReadSearchSpace(reader, *space, "study.space"));
  if (absl::Status status = run::ValidateStudyKeyPaths(spec.space); !status.ok()) {
    return absl::InvalidArgumentError(absl::StrCat(where, ": study.space: ", status.message()));
  }
  YAML::Emitter emitter;
  emitter << *space;
  spec.study.space = emitter.c_str();
  DCS_RETURN_IF_ERROR(CheckSamples(spec, where));
  return spec;
}

}  // namespace dcs::coordinator
