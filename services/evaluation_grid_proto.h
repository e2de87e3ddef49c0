// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_EVALUATION_GRID_PROTO_H_
#define DCS_SERVICES_EVALUATION_GRID_PROTO_H_

// A grid of contexts (actor/context_grid.h) as it travels to the cluster's actors
// (v1::EvaluationGrid): axes by feature name, resolved against the environment where the cells
// are evaluated. Thread-safe (pure functions).

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/context_grid.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "env/context_feature.h"

namespace dcs::services {

// One axis by its feature's name (`dcs eval -o json` shows them so too).
v1::GridAxis GridAxisToProto(const actor::GridAxis& axis);

v1::EvaluationGrid EvaluationGridToProto(const std::vector<actor::GridAxis>& axes,
                                         uint64_t seed);

// The number of cells of `grid`. INVALID_ARGUMENT for no axis or more than two, an axis of
// fewer than one value, or more cells than an int holds.
absl::StatusOr<int> GridCellCount(const v1::EvaluationGrid& grid);

// `grid`'s axes, their features resolved in `space`. INVALID_ARGUMENT as GridCellCount, for
// an axis actor::MakeGridAxis refuses, or for a feature named twice.
absl::StatusOr<std::vector<actor::GridAxis>> GridAxesFromProto(const env::ContextSpace& space,
                                                               const v1::EvaluationGrid& grid);

}  // namespace dcs::services

#endif  // DCS_SERVICES_EVALUATION_GRID_PROTO_H_
