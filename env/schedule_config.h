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
// and periods are in environment steps. Parameters per family, each with its allowed range and
// the builder's default in brackets (span = max - min). Kinds of value that need no range of
// their own:
//   magnitude      a number >= 0, absolute or as `<name>_frac` (>= 0, times the scale given)
//   magnitude range  [lo, hi] of magnitudes with 0 <= lo <= hi
//   interval       [lo, hi] in whole steps with 1 <= lo <= hi: each one drawn from U{lo..hi}
//   values         numbers within [min, max]
//   probability    a number in [0, 1]
//
//   identity (alias constant)   -
//   sinusoidal          amplitude | amplitude_frac: magnitude (of span/2) [0];
//                       period >= 1 [1]; initial_direction random|down|up [random]
//   cosine_annealing    T_0: whole steps >= 1 (required; mode once: [200]);
//                       T_mult: whole >= 1 [1]; mode cycle|once [cycle];
//                       T_max: whole steps >= 1 [1000];
//                       start, end (once only): in [min, max] [the episode-initial value, an
//                       edge]; neighborhood_radius | neighborhood_radius_frac: magnitude (of
//                       span/2) [none]; direction auto|to_min|to_max|random [auto];
//                       retarget swap|restart|random [restart]; min_delta >= 0 [0];
//                       repel_edge_eps_frac in [0, 0.5] [0.05]
//   continuous_incrementer  delta | delta_frac: magnitude (of span) (required);
//                       direction positive|negative|both [both]; direction_prob: probability
//                       [0.5]; edge_mode clip|reflect [reflect]; episode_direction
//                       none|up|down|random [random]; noise_std >= 0 [0];
//                       follow_predefined_prob: probability [0.8]
//   random_walk         std | std_frac: magnitude (of span) [0.01]
//   piecewise_constant  values (required); interval_range: interval [30, 50]
//   sudden_jump         step_size_range | step_size_frac_range: magnitude range [0.1, 0.3];
//                       interval_range: interval [10, 30]; direction [both];
//                       direction_prob: probability [0.5]; edge_mode [clip]
//   ornstein_uhlenbeck  theta in [0, 1] [0.05]; mu: in [min, max], or initial |
//                       mu_frac in [0, 1] [midpoint]; sigma | sigma_frac: magnitude (of
//                       span) [0.08]
//   sinusoidal_jump     amplitude | amplitude_frac: magnitude (of span/2) [0.3];
//                       period >= 1 [100]; step_size_range | step_size_frac_range: magnitude
//                       range [0.2, 0.4]; interval_range: interval [80, 150]
//   phased_ou           theta in [0, 1] [0.05]; sigma | sigma_frac: magnitude (of span)
//                       [0.04]; values [min, mid, max]; interval_range: interval [100, 150]
//   levy_walk           std | std_frac: magnitude (of span) [0.008]; step_size_range |
//                       step_size_frac_range: magnitude range [0.2, 0.4]; interval_range:
//                       interval [40, 80]
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
