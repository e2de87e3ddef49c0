// Copyright 2026 The DCS Authors.
#include "run/config_keys.h"

#include <cmath>

namespace dcs::run {

bool Bound::bounded() const { return !std::isinf(lo) || !std::isinf(hi) || lo_open; }

bool Bound::Contains(double value) const {
  return std::isfinite(value) && (lo_open ? value > lo : value >= lo) && value <= hi;
}

std::string Bound::Rule() const {
  if (std::isinf(hi)) {
    if (!lo_open) return absl::StrCat("at least ", lo);
    return lo == 0 ? "positive" : absl::StrCat("greater than ", lo);
  }
  if (std::isinf(lo)) return absl::StrCat("at most ", hi);
  return absl::StrCat("in ", lo_open ? "(" : "[", lo, ", ", hi, "]");
}

}  // namespace dcs::run
