// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SWEEP_SPEC_YAML_H_
#define DCS_RUN_SWEEP_SPEC_YAML_H_

// Sweep specs (run/sweep_spec.h) read from YAML, as `dcs submit` and configs/ write them,
// and validated whole: every run the sweep would make is checked as a run config is
// (run/run_spec_yaml.h) before anything is stored. An example (docs/config.md lists every key,
// made from the tables the reader takes its keys from: SweepSpecReference):
//
//   name: quickstart          # optional (default: none; the client uses the file's name)
//   seeds: 3                  # required. N: seeds 0..N-1; or a list of distinct seeds [0, 5, 7]
//   observe: [none, live]     # each condition in each of these modes, in order; a single mode
//                             # is a list of one; absent: [none]
//   env: cartpole             # the base of every run: the run config's keys but seed,
//   total_timesteps: 150000   # schedule, stages and observe
//   feature: length
//   training_range: [0.35, 0.75]
//   pool: {size: 7}
//   evaluation: {contexts: {id: [0.4, 0.5], ood_low: [0.1], ood_high: [1.0]}}
//   ppo: {n_epochs: 10}
//   conditions:
//     - name: static          # neither schedule nor stages: the static baseline
//     - schedule: {family: sinusoidal, period: 125}
//       grid: {schedule.amplitude_frac: [0.25, 0.5]}   # one condition per value
//     - name: curriculum
//       stages:
//         - {steps: 30000, schedule: {family: constant}}
//         - {steps: 120000, schedule: {family: cosine_annealing, T_0: 250}}
//     - name: pool15
//       pool: {size: 15}      # a condition may override any base key (not seed)
//       ppo: {n_epochs: 5}    # context, evaluation, ppo, coverage merge key by key
//       observe: live         # its own modes, instead of the sweep's
//
// A `study:` block makes the sweep a search over its one condition's config (TPE or random
// sampling, coordinator/study_sweep_spec.h, which reads the block); here it is only noted
// (SweepSpec::study), the rest of the spec read as any sweep's.
//
// A condition holds `name`, `grid`, `observe`, `schedule` or `stages` (not both), and any base
// key. A base key the condition gives replaces the base's whole (`pool` too), except the
// mappings `context`, `evaluation`, `ppo` and `coverage`, whose keys the condition's replace one
// by one (one level deep: a condition's `evaluation: {contexts: ...}` replaces all the contexts).
//
// `grid` maps key paths within the condition's run config (`schedule.period`, `pool.size`,
// `n_envs`, `ppo.learning_rate`, `stages[1].schedule.T_0`) to non-empty lists of values; the
// condition becomes one condition per combination, the first key varying slowest. A value goes
// where the condition would have written it (so it merges as the condition's own keys do): the
// mappings on its path are created if the condition lacks them; a list index needs the item in
// the condition. Two grid keys may not overlap (`schedule` and `schedule.period`), nor a list
// hold a value twice. A key with an index is written in a block mapping or quoted
// (`grid: {"stages[1].steps": [10, 20]}`): in a flow mapping '[' would start a list.
//
// Names: a condition's `name`, else "static" (no schedule), its schedule's family as written
// ("sinusoidal"), or its stages' families joined by '>' ("constant>cosine_annealing"); then,
// for each grid key in order, " <the key's last part>=<the value as written>"
// ("sinusoidal amplitude_frac=0.25"). Names are unique in the sweep, not empty, and hold no '/'
// and no control characters (they name files and table rows).
//
// The trials are the conditions in order, each in its modes in order; a sweep makes one run per
// trial and seed, at most 10,000 runs, and needs at least one condition and one seed. A trial's
// family is "static" (no schedule), its one schedule's family as env::ScheduleFamilyName spells
// it (`constant` is "identity"), or "multi_stage" (two or more stages); the first static
// condition is the sweep's baseline.
//
// Errors are one INVALID_ARGUMENT listing every problem found, each as a run config's error
// reads, "<where>: <path>: line <n>: <message>" (run/config_errors.h), with the path and line
// in the spec where the field was written: `conditions[2].stages[1].schedule.period` for a key
// of a condition, `conditions[1].grid.schedule.amplitude_frac[1]` for a grid value (and
// `conditions[1].grid.schedule.period`, with no line, for a mapping the grid key created),
// `ppo.gamma` for a base key. One problem reads exactly so; several read
//
//   3 problems in sweep.yaml:
//     sweep.yaml: conditions: line 12: ...
//     ...
//
// Found: malformed YAML (alone: nothing else is read); the sweep's own keys (unknown keys,
// `seed`, `schedule` or `stages` at the top level, seeds, modes, the grid, names, the number of
// runs); and the first error of each trial's run config, once per distinct message (so a bad
// base key is reported once, not once per trial).
//
// Thread-safe (pure functions).

#include <yaml-cpp/yaml.h>

#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/config_doc.h"
#include "run/sweep_spec.h"
#include "run/yaml_reader.h"

namespace dcs::run {

// A sweep spec's keys as docs/config.md shows them: the top level's ("") and a condition's
// ("conditions[i]"), from the tables the reader takes the keys it allows from.
std::vector<KeySection> SweepSpecReference();

// The sweep spec in `text`, expanded and validated; `where` names it in errors (its file path).
// INVALID_ARGUMENT for every problem listed above, and as ParseRunSpecYaml for each trial.
absl::StatusOr<SweepSpec> ParseSweepSpecYaml(absl::string_view text, absl::string_view where);

// The sweep spec `root`, a document `reader` loaded (which names it in errors), read as
// ParseSweepSpecYaml reads its text, with the same errors: for a caller that reads more of the
// document (a study sweep's `study:` block, coordinator/study_sweep_spec.h) without loading it
// again. `root` is left as it was.
absl::StatusOr<SweepSpec> ReadSweepSpec(const YamlReader& reader, const YAML::Node& root);

}  // namespace dcs::run

#endif  // DCS_RUN_SWEEP_SPEC_YAML_H_
