// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SWEEP_SPEC_H_
#define DCS_RUN_SWEEP_SPEC_H_

// A sweep as a user specifies it (run/sweep_spec_yaml.h), expanded: its trials (each condition
// of the grid in each of its observation modes), each with its run config, and the seeds every
// trial is trained with. A sweep trains one run per trial and seed. Plain data; thread-safe.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "env/observe_mode.h"
#include "run/run_spec.h"

namespace dcs::run {

// One condition of the sweep in one observation mode. The pair (condition, observe) is the
// trial's identity within its sweep.
struct SweepTrial {
  std::string condition;  // its condition's name, unique in the sweep
  // "static" (no schedule), the family of its one schedule as env::ScheduleFamilyName spells
  // it ("sinusoidal"; `constant` is "identity"), or "multi_stage" for two or more stages.
  std::string family;
  env::ObserveMode observe = env::ObserveMode::kNone;
  // The trial's run config as YAML text without a `seed` key (a run adds its own,
  // run::ConfigWithSeed): ParseRunSpecYaml accepts it and reads `spec`.
  std::string config;
  // The run config as the sweep's validation read it (its seed the default): the trial's runs
  // are made from it and `config` (run/seeded_runs.h), not read again.
  RunSpec spec;
};

struct SweepSpec {
  std::string name;  // empty if the spec gives none
  std::vector<uint64_t> seeds;  // distinct, in the spec's order
  // Conditions in the spec's order (each grid expanded in place), each in its modes in order.
  std::vector<SweepTrial> trials;
  // The first condition whose family is "static", if any: what reports compare against.
  std::optional<std::string> baseline;
  // Whether the spec has a `study` block: a search over the runs' configs, read (and checked)
  // by coordinator/study_sweep_spec.h, not here.
  bool study = false;
};

}  // namespace dcs::run

#endif  // DCS_RUN_SWEEP_SPEC_H_
