// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SCHEDULE_YAML_H_
#define DCS_COORDINATOR_SCHEDULE_YAML_H_

// Schedule configs (env/schedule_config.h) read from YAML, as sweep specs and
// `dcs schedule preview --spec FILE` write them:
//
//   family: cosine_annealing
//   T_0: 250
//   neighborhood_radius_frac: 0.2
//   direction: random
//
// A parameter is a number, a word, or a list of numbers; a sequential schedule lists its parts
// under `parts`. Thread-safe (pure functions).

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "env/schedule_config.h"

namespace dcs::coordinator {

// The schedule config in `node` (a mapping with `family`). INVALID_ARGUMENT naming `where`,
// the line and the key for anything else: a missing family, a nested mapping, a list of
// non-numbers.
absl::StatusOr<env::ScheduleConfig> ScheduleConfigFromYaml(const YAML::Node& node,
                                                           absl::string_view where);

// The schedule configs of a YAML document: one mapping, or a list of them. INVALID_ARGUMENT
// for malformed YAML (with the line) or as above.
absl::StatusOr<std::vector<env::ScheduleConfig>> ParseScheduleConfigsYaml(absl::string_view text,
                                                                          absl::string_view where);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SCHEDULE_YAML_H_
