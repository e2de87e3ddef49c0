// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SCHEDULE_YAML_H_
#define DCS_RUN_SCHEDULE_YAML_H_

// Schedule configs (env/schedule_config.h) read from YAML, as run configs, sweep specs and
// `dcs schedule preview FILE` write them:
//
//   family: cosine_annealing
//   T_0: 250
//   neighborhood_radius_frac: 0.2
//   direction: random
//
// A parameter is a number, a word, or a list of numbers, by the number rule of
// run/yaml_reader.h (so `period: "125"` is a word, and `period: nan` an error); a sequential
// schedule lists its parts under `parts`. Which parameters a family takes, and their ranges,
// are checked later by env::ParseScheduleSpec; ScheduleError places its errors at the
// parameter's path and line. Thread-compatible (the reader notes lines).

#include <vector>

#include <yaml-cpp/yaml.h>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "env/schedule_config.h"
#include "run/yaml_reader.h"

namespace dcs::run {

// The schedule config in `node`, at `path` (a mapping with `family`). INVALID_ARGUMENT naming
// the path and line for anything else: a missing family, a repeated key, a nested mapping, a
// list of non-numbers, a non-finite number.
absl::StatusOr<env::ScheduleConfig> ReadScheduleConfig(YamlReader& reader, const YAML::Node& node,
                                                       absl::string_view path);

// The schedule configs of a YAML document named `where`: one mapping, or a list of them.
// INVALID_ARGUMENT for malformed YAML (with the line) or as above.
absl::StatusOr<std::vector<env::ScheduleConfig>> ParseScheduleConfigsYaml(absl::string_view text,
                                                                          absl::string_view where);

// An error of env::ParseScheduleSpec for the schedule read at `path`, placed at the parameter
// it names (ErrorField, common/status_util.h): "stages[1].schedule.period", with its line.
absl::Status ScheduleError(const ConfigErrors& errors, absl::string_view path,
                           const absl::Status& status);

}  // namespace dcs::run

#endif  // DCS_RUN_SCHEDULE_YAML_H_
