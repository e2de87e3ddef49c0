// Copyright 2026 The DCS Authors.
#include "env/context_feature.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"
#include "common/status_util.h"

namespace dcs::env {

float NormalizeContext(const ContextFeature& feature, double value) {
  const double mid = 0.5 * (feature.normalization_lower + feature.normalization_upper);
  const double half =
      std::max(1e-8, 0.5 * (feature.normalization_upper - feature.normalization_lower));
  return static_cast<float>(std::clamp((value - mid) / half, -5.0, 5.0));
}

absl::StatusOr<int> ContextSpace::IndexOf(absl::string_view name) const {
  for (int i = 0; i < size(); ++i) {
    if (features_[i].name == name) return i;
  }
  return absl::InvalidArgumentError(absl::StrCat(
      "unknown context feature '", name, "' (known: ",
      absl::StrJoin(features_, ", ",
                    [](std::string* out, const ContextFeature& f) { out->append(f.name); }),
      ")"));
}

absl::Status ContextSpace::Validate(int index, double value) const {
  const ContextFeature& f = features_[index];
  if (!std::isfinite(value) || value < f.lower || value > f.upper) {
    return absl::InvalidArgumentError(absl::StrCat("context feature '", f.name, "' must be in [",
                                                   f.lower, ", ", f.upper, "], got ", value));
  }
  return absl::OkStatus();
}

std::vector<double> ContextSpace::Defaults() const {
  std::vector<double> values;
  values.reserve(features_.size());
  for (const ContextFeature& f : features_) values.push_back(f.default_value);
  return values;
}

absl::StatusOr<std::vector<double>> ContextSpace::WithValues(
    const std::map<std::string, double>& values) const {
  std::vector<double> context = Defaults();
  for (const auto& [name, value] : values) {
    absl::StatusOr<int> index = IndexOf(name);
    if (!index.ok()) return ErrorInField(index.status(), name);
    DCS_RETURN_IF_ERROR(ErrorInField(Validate(*index, value), name));
    context[*index] = value;
  }
  return context;
}

}  // namespace dcs::env
