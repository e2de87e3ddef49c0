// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_SPEC_YAML_H_
#define DCS_RUN_RUN_SPEC_YAML_H_

// Training-run configs (run/run_spec.h) read from YAML, as `dcs train run.yaml`
// and the files in configs/ write them, and their validation against the environment. An
// example (docs/config.md lists every key with its type, default, range and meaning, made from
// the tables the reader and the checks use: RunConfigReference):
//
//   env: cartpole
//   seed: 0
//   total_timesteps: 150000
//   context: {masspole: 0.1}  # other features' values, by name (default: their defaults)
//   feature: length           # the varied feature
//   training_range: [0.35, 0.75]
//   pool: {size: 7}           # or {values: [0.35, 0.41, 0.48, 0.55, 0.62, 0.68, 0.75]}
//   schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}   # or:
//   stages:                   # multi-stage; not together with `schedule`
//     - {steps: 30000, schedule: {family: constant}}
//     - {steps: 120000, schedule: {family: cosine_annealing, T_0: 250}}
//   observe: live
//   evaluation:
//     freq: 10000             # environment steps between evaluations (and one at the end)
//     episodes: 30            # per context
//     contexts: {id: [0.37, 0.5, 0.6, 0.71], ood_low: [0.06, 0.09, 0.12], ood_high: [0.92, 1.32]}
//   ppo: {learning_rate: 3.0e-4, n_epochs: 10, context_layers: []}  # context_layers: images
//
// Meanings: docs/reference.md, "Parameters as fractions of the range" (schedule parameters, as
// fractions of the training range), "Pools", "Multi-stage schedules", "Evaluation protocol";
// "Evaluation grids" (ranges and grids per environment) and "Settings per experiment" (PPO). `pool`
// is {size: N} (pool-N over the training range) or {values: [...]} (exactly these, each inside the
// training range), not both; absent, pool-1 (the midpoint). No `schedule` and no `stages`: the
// feature is static within episodes (identity). `schedule` alone is one stage of steps 0, which
// runs for the whole run; each of a list of stages runs for its `steps` environment steps, and the
// last one stays in force after its steps are over (env/staged_schedule.h). `clip_range_vf` and
// `target_kl` take null for none. Schedules are read by ReadScheduleConfig (run/schedule_yaml.h);
// numbers follow the rule of run/yaml_reader.h.
//
// Errors are INVALID_ARGUMENT, as "<where>: <path>: line <n>: <message>": `path` is the YAML
// path of the field (`evaluation.contexts.ood_high[2]`, `stages[1].schedule.period`,
// `ppo.gamma`), the line is given when the field is in the text, and the message says what is
// allowed.
//
// Thread-safe (pure functions).

#include <yaml-cpp/yaml.h>

#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/config_doc.h"
#include "run/config_errors.h"
#include "run/config_keys.h"
#include "run/run_spec.h"
#include "run/yaml_reader.h"

namespace dcs::run {

// Parses the run config in `text`, then validates it (ValidateRunSpec); `where` names the text
// in errors (e.g. its file path). INVALID_ARGUMENT for malformed YAML (with its line and
// column); for an unknown or repeated key at any level (naming the key, its path and the keys
// allowed there); for a value of the wrong type (a string or null where a number is expected, a
// fraction where an integer is, a mapping where a list is, a quoted number, a number that is not
// finite), naming its path; for an `observe` mode other than none, initial or live; for
// `schedule` given together with `stages`, or `pool` with both `size` and `values`; and for
// anything ValidateRunSpec refuses.
absl::StatusOr<RunSpec> ParseRunSpecYaml(absl::string_view text, absl::string_view where);

// The run config `root` (a document loaded by `reader`, or assembled from one's nodes, as a
// sweep spec's trials are: run/sweep_spec_yaml.h), read and validated as ParseRunSpecYaml does,
// with the same errors; `reader` names the document and shows the paths (run/yaml_reader.h).
// Every problem found is reported, together (run/config_errors.h: ConfigProblems): each field's
// own checks run whatever the others found; a key that cannot be read stops validation (whose
// checks would see defaults), an unknown environment the checks that need it.
absl::StatusOr<RunSpec> ReadRunSpec(YamlReader& reader, const YAML::Node& root);
// The same, adding each problem to `problems`; the spec if there were none.
std::optional<RunSpec> ReadRunSpec(YamlReader& reader, const YAML::Node& root,
                                   ConfigProblems& problems);

// The run config's top-level keys (run/config_keys.h): the keys ReadRunSpec allows there, reads
// and checks, which docs/config.md shows; a sweep spec's base keys are among them
// (run/sweep_spec_yaml.h).
const KeyTable<RunSpec>& RunConfigKeys();
// Every mapping's keys of a run config as docs/config.md shows them, by the mapping's path:
// "" (the top level), "pool", "stages[i]", "evaluation", "evaluation.contexts", "ppo" and
// "coverage"; each from the table its reader and checks use.
std::vector<KeySection> RunConfigReference();

// OK if `spec` is a run its environment can carry out, else INVALID_ARGUMENT naming each
// offending field (all of them, as ReadRunSpec) by its YAML path and saying what is allowed:
//   - `env` is a known environment (env/env_registry.h);
//   - every `context` name is a feature of it other than the varied one, with a value within the
//     feature's physical bounds, and the full context passes the environment's ValidateContext
//     at every training and evaluation value of the varied feature;
//   - `feature` is a feature of it; `training_range` is finite with lo < hi, both within the
//     feature's physical bounds;
//   - `pool.values` lie within the training range, or 1 <= `pool.size` <= 10000;
//   - every stage's schedule is valid over the training range (env::ParseScheduleSpec); stage
//     steps are positive, except a single stage of steps 0 (the whole run); every stage starts
//     before `total_timesteps` (a later one would never run);
//   - `evaluation.freq` >= 1, `evaluation.episodes` >= 1, at least one evaluation context, each
//     within the feature's physical bounds (not the training range: OOD values are the point);
//   - `total_timesteps` >= 1, `n_envs` >= 1, and `ppo` passes ValidatePpoConfig.
absl::Status ValidateRunSpec(const RunSpec& spec);

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_SPEC_YAML_H_
