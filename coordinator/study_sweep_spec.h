// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STUDY_SWEEP_SPEC_H_
#define DCS_COORDINATOR_STUDY_SWEEP_SPEC_H_

// A study sweep: a sweep spec (run/sweep_spec_yaml.h) with a `study:` block, which makes it a
// search over its one condition's run config, as the paper's multi-stage search is
// (docs/reference.md, "Multi-stage schedules"). The coordinator asks the study's sampler for a
// trial, trains the trial's run config with each of the sweep's seeds, tells the sampler the
// objective, and keeps `parallel` trials training at once (coordinator/study_sweep.h). An example:
//
//   name: cartpole_multistage_search
//   seeds: 4                      # every trial trains with each of these seeds
//   observe: [live]
//   env: cartpole                 # ...the base keys of every run, as in any sweep
//   conditions:
//     - name: search              # one condition in one mode: the base of every trial
//       stages:
//         - {steps: 30000, schedule: {family: constant}}
//         - {steps: 120000, schedule: {family: constant}}
//   study:
//     trials: 240                 # required: how many trials the study asks for
//     parallel: 4                 # trials training at once (default 1)
//     sampler: tpe                # tpe (default) | random
//     seed: 0                     # the sampler's (default 0)
//     tpe: {startup_trials: 10, ei_candidates: 24, multivariate: false, group: false,
//           constant_liar: false}          # TPE's options (these are the defaults)
//     objective: best_anytime     # best_anytime (default) | last_iqm
//     pruner: {kind: median}      # none (default) | median | successive_halving, with options
//     retrain: {top_k: 20, seeds: 10}      # default none
//     space:                      # a search space (run/search_space_yaml.h) whose parameters
//       parameters:               # are named by key paths of the condition's run config
//         - {name: "stages[0].schedule.family", type: categorical,
//            choices: [constant, sinusoidal]}
//         - {name: "stages[0].schedule.period", type: int, low: 25, high: 500, log: true,
//            when: {"stages[0].schedule.family": sinusoidal}}
//
// Objectives (maximised): `best_anytime`, the paper's, is the mean over seeds of each seed's
// best avg_combined at a stage boundary or the end (EvaluationLog.best_anytime); `last_iqm` the
// interquartile mean over seeds of the last evaluation's avg_combined.
//
// The pruner's options are those of `dcs studies create`: median takes percentile [50],
// startup_trials [5], warmup_steps [0], interval_steps [1], min_trials [1]; successive_halving
// takes min_resource [auto], reduction_factor [4], min_early_stopping_rate [0],
// bootstrap_count [0]. A trial reports the objective as it stands at each stage boundary (the
// step is the boundary's, in environment steps); a pruned trial's runs are cancelled.
//
// `retrain` re-runs the `top_k` best complete trials once every trial has finished, each with
// `seeds` new seeds: N for the N seeds after the search's largest, or a list; never a seed of
// the search (its run would repeat bit for bit, selection bias and all).
//
// Errors: those of ParseSweepSpecYaml first; then one INVALID_ARGUMENT naming the path and line
// of the first problem of the study block: an unknown or missing key, a value out of range, a
// space that does not validate or whose names are not key paths of the run config, or a sample
// of the space whose run config does not validate. A study sweep has exactly one trial (one
// condition in one observation mode). Thread-safe (pure functions).

#include <cstdint>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/enum_names.h"
#include "coordinator/study_table.h"
#include "run/search_space.h"
#include "run/sweep_spec.h"
#include "run/yaml_reader.h"

namespace dcs::coordinator {

enum class StudyObjective { kBestAnytime, kLastIqm };
inline constexpr EnumName<StudyObjective> kStudyObjectiveNames[] = {
    {StudyObjective::kBestAnytime, "best_anytime"}, {StudyObjective::kLastIqm, "last_iqm"}};
static_assert(InEnumOrder(kStudyObjectiveNames));

struct StudySweepSpec {
  run::SweepSpec sweep;  // exactly one trial: the base of every study trial's run config
  // The study (request id and name left to the submission; direction maximize). Its `space` is
  // the YAML text of the block's space.
  StudySubmission study;
  run::SearchSpace space;
  int trials = 0;
  int parallel = 1;
  StudyObjective objective = StudyObjective::kBestAnytime;
  int retrain_top_k = 0;  // 0: no retraining
  std::vector<uint64_t> retrain_seeds;
};

// The study sweep in `text` (named `where` in errors). INVALID_ARGUMENT as listed above, and
// for a spec without a `study:` block.
absl::StatusOr<StudySweepSpec> ParseStudySweepYaml(absl::string_view text, absl::string_view where);

// The study sweep of `sweep`, the sweep spec `reader` read from the document `root`
// (run::ReadSweepSpec): its `study:` block read from `root`, without loading the text again.
// INVALID_ARGUMENT as ParseStudySweepYaml after its sweep spec.
absl::StatusOr<StudySweepSpec> ReadStudySweep(run::YamlReader& reader, const YAML::Node& root,
                                              run::SweepSpec sweep);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STUDY_SWEEP_SPEC_H_
