// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CONTEXT_FEATURE_H_
#define DCS_ENV_CONTEXT_FEATURE_H_

// Context features: the named physical parameters of an environment that a context sets
// (CARL's "context features": pole length, gravity, payload position, ...), with the bounds a
// value must respect and the "sensor" bounds used to normalise it when the policy observes it.
// Immutable after construction; thread-safe.

#include <map>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"

namespace dcs::env {

struct ContextFeature {
  std::string name;  // as configs spell it: "length"
  std::string description;
  double default_value = 0;
  // Physical bounds: a context outside them is refused (may be infinite).
  double lower = 0;
  double upper = 0;
  // Normalisation ("sensor") bounds, always finite: an observed value x is shown to the policy
  // as clip((x - mid) / half, -5, 5) with mid and half of this interval (docs/reference.md,
  // "Observation modes and normalisation"). Deliberately wider than any training or evaluation
  // range, so the evaluation grid is not encoded in the input.
  double normalization_lower = -1;
  double normalization_upper = 1;
};

// The observed form of a feature value: (x - mid) / half of the normalisation bounds, clipped
// to [-5, 5] (the reference ContextOnlyNormalize).
float NormalizeContext(const ContextFeature& feature, double value);

// The features of one environment, in a fixed order: a feature's index is its position.
class ContextSpace {
 public:
  explicit ContextSpace(std::vector<ContextFeature> features) : features_(std::move(features)) {}

  std::span<const ContextFeature> features() const { return features_; }
  int size() const { return static_cast<int>(features_.size()); }
  const ContextFeature& feature(int index) const { return features_[index]; }

  // The index of the feature called `name`. INVALID_ARGUMENT, listing the known names, if none.
  absl::StatusOr<int> IndexOf(absl::string_view name) const;

  // OK if `value` is a valid value of feature `index`: finite and within its physical bounds.
  // INVALID_ARGUMENT naming the feature and its bounds otherwise.
  absl::Status Validate(int index, double value) const;

  // Every feature's default value, by index.
  std::vector<double> Defaults() const;

  // The defaults with `values` (feature name -> value) in place of theirs. INVALID_ARGUMENT,
  // with the feature's name as the error's field (common/status_util.h), for a name IndexOf
  // does not know or a value Validate refuses.
  absl::StatusOr<std::vector<double>> WithValues(const std::map<std::string, double>& values) const;

 private:
  std::vector<ContextFeature> features_;
};

}  // namespace dcs::env

#endif  // DCS_ENV_CONTEXT_FEATURE_H_
