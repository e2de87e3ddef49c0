// Copyright 2026 The DCS Authors.
#include "services/evaluation_grid_proto.h"

#include <limits>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"

namespace dcs::services {

v1::GridAxis GridAxisToProto(const actor::GridAxis& axis) {
  v1::GridAxis out;
  out.set_feature(axis.name);
  out.set_low(axis.low);
  out.set_high(axis.high);
  out.set_count(axis.count);
  return out;
}

v1::EvaluationGrid EvaluationGridToProto(const std::vector<actor::GridAxis>& axes,
                                         uint64_t seed) {
  v1::EvaluationGrid grid;
  for (const actor::GridAxis& axis : axes) *grid.add_axes() = GridAxisToProto(axis);
  grid.set_seed(seed);
  return grid;
}

absl::StatusOr<int> GridCellCount(const v1::EvaluationGrid& grid) {
  if (grid.axes().empty() || grid.axes_size() > 2) {
    return absl::InvalidArgumentError(
        absl::StrCat("a grid has one or two axes, not ", grid.axes_size()));
  }
  int64_t cells = 1;
  for (const v1::GridAxis& axis : grid.axes()) {
    if (axis.count() < 1) {
      return absl::InvalidArgumentError(absl::StrCat("the grid axis of '", axis.feature(),
                                                     "' has ", axis.count(), " values"));
    }
    cells *= axis.count();
  }
  if (cells > std::numeric_limits<int>::max()) {
    return absl::InvalidArgumentError(absl::StrCat("a grid of ", cells, " cells is too large"));
  }
  return static_cast<int>(cells);
}

absl::StatusOr<std::vector<actor::GridAxis>> GridAxesFromProto(const env::ContextSpace& space,
                                                               const v1::EvaluationGrid& grid) {
  DCS_RETURN_IF_ERROR(GridCellCount(grid).status());
  std::vector<actor::GridAxis> axes;
  for (const v1::GridAxis& axis : grid.axes()) {
    DCS_ASSIGN_OR_RETURN(actor::GridAxis resolved,
                         actor::MakeGridAxis(space, axis.feature(), axis.low(), axis.high(),
                                             axis.count()));
    if (!axes.empty() && axes.front().feature == resolved.feature) {
      return absl::InvalidArgumentError(
          absl::StrCat("the grid names feature '", resolved.name, "' twice"));
    }
    axes.push_back(std::move(resolved));
  }
  return axes;
}

}  // namespace dcs::services
