// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_SEARCH_SPACE_YAML_H_
#define DCS_RUN_SEARCH_SPACE_YAML_H_

// Search spaces (run/search_space.h) read from YAML, as `dcs studies create FILE` takes
// them: the parameters in the order a trial suggests them.
//
//   parameters:
//     - {name: x1, type: float, low: -5, high: 10}
//     - {name: lr, type: float, low: 1e-5, high: 1e-2, log: true}
//     - {name: frac, type: float, low: 0, high: 1, step: 0.25}
//     - {name: layers, type: int, low: 1, high: 4}           # also log: true, step: N
//     - {name: mode, type: categorical, choices: [constant, sinusoidal]}
//     - {name: period, type: int, low: 10, high: 500, log: true,
//        when: {mode: sinusoidal}}                            # or when: {mode: [a, b]}
//
// `when` makes a parameter conditional: it exists only when the named earlier categorical took
// one of the choices. docs/config.md lists every key (SearchSpaceReference). Thread-compatible.

#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/config_doc.h"
#include "run/search_space.h"
#include "run/yaml_reader.h"

namespace dcs::run {

// The search space in `node` (a mapping with `parameters`), at `path`. INVALID_ARGUMENT naming
// the path and line for a malformed parameter (an unknown key or type, a bound that is not a
// number, a missing one), or the parameter and the problem for an invalid space
// (ValidateSearchSpace).
absl::StatusOr<SearchSpace> ReadSearchSpace(YamlReader& reader, const YAML::Node& node,
                                            absl::string_view path);

// A search space's keys as docs/config.md shows them: the top level's ("") and a parameter's
// ("parameters[i]"), from the tables the reader takes the keys it allows from.
std::vector<KeySection> SearchSpaceReference();

// The search space of a YAML document named `where`.
absl::StatusOr<SearchSpace> ParseSearchSpaceYaml(absl::string_view text, absl::string_view where);

}  // namespace dcs::run

#endif  // DCS_RUN_SEARCH_SPACE_YAML_H_
