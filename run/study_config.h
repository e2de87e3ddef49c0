// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_STUDY_CONFIG_H_
#define DCS_RUN_STUDY_CONFIG_H_

// A study over run configs: each parameter of the search space is named by the key path in a run
// config where its value goes (run/yaml_splice.h: `stages[1].schedule.family`,
// `stages[1].schedule.period`, `ppo.learning_rate`), so that a trial's run config is a base
// config with the trial's values written in, as a sweep's grid values are. The paper's multi-stage
// search is such a space over a base whose stages give only their steps: each stage's family is a
// categorical parameter, and each family's parameters are conditional on it. Thread-safe (pure
// functions).

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "run/search_space.h"
#include "run/seeded_runs.h"

namespace dcs::run {

// INVALID_ARGUMENT naming the parameter if a name of `space` is not a key path, or if two
// parameters' paths overlap (`schedule` and `schedule.period`).
absl::Status ValidateStudyKeyPaths(const SearchSpace& space);

// The run config of a trial, as YAML text and as read (the runs of its seeds): `base` (a run
// config without its seed; `where` names it in errors) with each of the trial's `values`
// (internal representation, as a sampler gives them) at its parameter's key path: a
// categorical's choice as a word, an int as an integer, a float with the digits that read back
// to it. Mappings on a path that the base lacks are created. The result is read and checked as
// a run config is (ParseRunSpecYaml), with errors at the paths where the values went.
// INVALID_ARGUMENT for a path that cannot be taken (a key into a list, an index past its end), a
// value of no parameter of the space, or a run config that does not validate.
absl::StatusOr<SeededRuns> TrialRunConfig(absl::string_view base, absl::string_view where,
                                          const SearchSpace& space, const ParameterValues& values);

}  // namespace dcs::run

#endif  // DCS_RUN_STUDY_CONFIG_H_
