// Copyright 2026 The DCS Authors.
#include "actor/context_grid.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace dcs::actor {

namespace {

// Why `axis`'s range is not one, or nullopt.
std::optional<std::string> RangeProblem(const GridAxis& axis) {
  if (axis.count < 1) return "N must be at least 1";
  if (!(axis.low <= axis.high)) return "LOW must not exceed HIGH";
  if (axis.count == 1 && axis.low != axis.high) return "one value needs LOW = HIGH";
  return std::nullopt;
}

// `axis` with its feature's index, once its feature and both ends are valid in `space`.
absl::StatusOr<GridAxis> ResolveFeature(const env::ContextSpace& space, GridAxis axis) {
  DCS_ASSIGN_OR_RETURN(axis.feature, space.IndexOf(axis.name));
  DCS_RETURN_IF_ERROR(space.Validate(axis.feature, axis.low));
  DCS_RETURN_IF_ERROR(space.Validate(axis.feature, axis.high));
  return axis;
}

}  // namespace

absl::StatusOr<GridAxis> ParseGridAxis(const env::ContextSpace& space, absl::string_view text) {
  const auto malformed = [text](absl::string_view why) {
    return absl::InvalidArgumentError(
        absl::StrCat("--grid '", text, "': ", why, " (FEATURE=LOW:HIGH:N, e.g. length=0.1:2:40)"));
  };
  const std::vector<absl::string_view> assignment = absl::StrSplit(text, absl::MaxSplits('=', 1));
  if (assignment.size() != 2) return malformed("no '='");
  const std::vector<absl::string_view> range = absl::StrSplit(assignment[1], ':');
  GridAxis axis{.name = std::string(assignment[0])};
  if (range.size() != 3 || !absl::SimpleAtod(range[0], &axis.low) ||
      !absl::SimpleAtod(range[1], &axis.high) || !absl::SimpleAtoi(range[2], &axis.count)) {
    return malformed("LOW:HIGH:N must be two numbers and a count");
  }
  if (const std::optional<std::string> why = RangeProblem(axis); why.has_value()) {
    return malformed(*why);
  }
  return ResolveFeature(space, std::move(axis));
}

absl::StatusOr<GridAxis> MakeGridAxis(const env::ContextSpace& space, std::string name,
                                      double low, double high, int count) {
  GridAxis axis{.name = std::move(name), .low = low, .high = high, .count = count};
  if (const std::optional<std::string> why = RangeProblem(axis); why.has_value()) {
    return absl::InvalidArgumentError(absl::StrCat("the grid axis of '", axis.name, "' (", low,
                                                   " to ", high, " in ", count,
                                                   " values): ", *why));
  }
  return ResolveFeature(space, std::move(axis));
}

size_t CellCount(const std::vector<GridAxis>& axes) {
  size_t cells = 1;
  for (const GridAxis& axis : axes) cells *= static_cast<size_t>(axis.count);
  return cells;
}

std::vector<double> CellValues(const std::vector<GridAxis>& axes, size_t cell) {
  std::vector<double> values;
  for (const GridAxis& axis : axes) {
    values.push_back(axis.value(static_cast<int>(cell % axis.count)));
    cell /= axis.count;
  }
  return values;
}

}  // namespace dcs::actor
