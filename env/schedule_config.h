// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_SCHEDULE_CONFIG_H_
#define DCS_ENV_SCHEDULE_CONFIG_H_

// Schedule configs as users write them (a family name and its parameters, e.g. from a YAML
// sweep spec), turned into a validated ScheduleSpec (env/schedule_spec.h).
//
//   family: sinusoidal
//   amplitude_frac: 0.25   # or amplitude: 0.05 (absolute units)
//   period: 125
//
// Every magnitude may be given in absolute units or as a fraction of the schedule's range
// (`<name>_frac`, as the reference builder takes them: docs/reference.md, "Parameters as
// fractions of the range"), not both; what is not given takes the builder's default. Intervals
// and periods are in environment steps. Each family's parameters, with their kinds, defaults and
// allowed ranges, are in docs/config.md ("Schedules"), which ScheduleFamilyReference makes from
// the readers in schedule_config.cc: what a reader checks is what the reference says.
//
// Thread-safe (pure functions).

#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "absl/status/statusor.h"
#include "common/config_doc.h"
#include "env/schedule_spec.h"

namespace dcs::env {

// A parameter's value: a number, a word, or a list of numbers (ranges are lists of two).
using ScheduleParam = std::variant<double, std::string, std::vector<double>>;

struct ScheduleConfig {
  std::string family;
  std::map<std::string, ScheduleParam> params;
  std::vector<ScheduleConfig> parts;  // `sequential` only
};

// The spec of `config` for a schedule bounded to [min_value, max_value] with base seed
// `seed`. INVALID_ARGUMENT naming the family and the field for an unknown family, an unknown,
// missing or ill-typed parameter, or a value outside its allowed range (given in the message),
// and for bounds that are not finite with min_value < max_value.
absl::StatusOr<ScheduleSpec> ParseScheduleSpec(const ScheduleConfig& config, double min_value,
                                               double max_value, uint32_t seed);

// Every problem ParseScheduleSpec finds in `config`, not only the first, each as it would report
// it: each parameter is checked whatever the others' checks found (a check between parameters,
// as `end` with mode cycle, once they are read). Empty if `config` is valid over
// [min_value, max_value]; validity does not depend on the seed.
std::vector<absl::Status> ScheduleConfigProblems(const ScheduleConfig& config, double min_value,
                                                 double max_value);

// The names ParseScheduleSpec knows, in the order of env/schedule_spec.h.
std::vector<std::string> ScheduleFamilyNames();

// A family's parameters as docs/config.md shows them, each described by the family's reader as
// it reads and checks it (kind, default, allowed range, meaning), in the order it reads them.
// Ranges that depend on the schedule's bounds name them "min" and "max"; "span" is max - min.
struct ScheduleFamilyDoc {
  std::string name;
  std::string alias;  // another name configs may use; empty if none
  std::vector<KeyDoc> parameters;
};
// Every family, in the order of ScheduleFamilyNames().
std::vector<ScheduleFamilyDoc> ScheduleFamilyReference();

}  // namespace dcs::env

#endif  // DCS_ENV_SCHEDULE_CONFIG_H_
