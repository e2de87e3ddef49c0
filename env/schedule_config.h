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
// (`<name>_frac`, as the reference builder takes them: docs/reference.md, "Parameters as fractions
// of the range"), not both; what is not given takes the builder's default. Intervals and periods
// are in environment steps. Parameters per family (builder defaults in brackets; span = max - min):
//   identity (alias constant)   -
//   sinusoidal          amplitude | amplitude_frac [0] (of span/2); period [0];
//                       initial_direction random|down|up [random]
//   cosine_annealing    T_0 (required); T_mult [1]; mode cycle|once [cycle]; T_max [1000];
//                       start, end (once only) [the episode-initial value, an edge];
//                       neighborhood_radius | neighborhood_radius_frac [none] (of span/2);
//                       direction auto|to_min|to_max|random [auto];
//                       retarget swap|restart|random [restart]; min_delta [0];
//                       repel_edge_eps_frac [0.05]
//   continuous_incrementer  delta | delta_frac (required); direction positive|negative|both
//                       [both]; direction_prob [0.5]; edge_mode clip|reflect [reflect];
//                       episode_direction none|up|down|random [random]; noise_std [0];
//                       follow_predefined_prob [0.8]
//   random_walk         std | std_frac [0.01]
//   piecewise_constant  values (required); interval_range [30, 50]
//   sudden_jump         step_size_range | step_size_frac_range [0.1, 0.3]; interval_range
//                       [10, 30]; direction [both]; direction_prob [0.5]; edge_mode [clip]
//   ornstein_uhlenbeck  theta [0.05]; mu | mu_frac | mu: initial [midpoint]; sigma | sigma_frac
//                       [0.08]
//   sinusoidal_jump     amplitude | amplitude_frac [0.3] (of span/2); period [100];
//                       step_size_range | step_size_frac_range [0.2, 0.4]; interval_range
//                       [80, 150]
//   phased_ou           theta [0.05]; sigma | sigma_frac [0.04]; values [min, mid, max];
//                       interval_range [100, 150]
//   levy_walk           std | std_frac [0.008]; step_size_range | step_size_frac_range
//                       [0.2, 0.4]; interval_range [40, 80]
//   sequential          parts: a list of schedule configs, applied in order
// Thread-safe (pure functions).

#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "absl/status/statusor.h"
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

}  // namespace dcs::env

#endif  // DCS_ENV_SCHEDULE_CONFIG_H_
