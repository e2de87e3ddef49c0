// Copyright 2026 The DCS Authors.
#include "coordinator/probability_of_improvement.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "common/random.h"
#include "common/status_macros.h"

namespace dcs::coordinator {
namespace {

absl::Status CheckSample(std::span<const double> values, absl::string_view name) {
  if (values.empty()) return absl::InvalidArgumentError(absl::StrCat("no runs in ", name));
  for (double value : values) {
    if (std::isnan(value)) {
      return absl::InvalidArgumentError(absl::StrCat("a run of ", name, " is NaN"));
    }
  }
  return absl::OkStatus();
}

// REQUIRES: both non-empty.
double PairwiseImprovement(std::span<const double> x, std::span<const double> y) {
  double wins = 0;  // in halves: a win counts 2, a tie 1, so the sum stays an exact integer
  for (double a : x) {
    for (double b : y) wins += a > b ? 2 : (a == b ? 1 : 0);
  }
  return wins / (2.0 * static_cast<double>(x.size()) * static_cast<double>(y.size()));
}

}  // namespace

absl::StatusOr<double> ProbabilityOfImprovement(std::span<const double> x,
                                                std::span<const double> y) {
  DCS_RETURN_IF_ERROR(CheckSample(x, "X"));
  DCS_RETURN_IF_ERROR(CheckSample(y, "Y"));
  return PairwiseImprovement(x, y);
}

absl::StatusOr<ConfidenceInterval> BootstrapImprovementInterval(std::span<const double> x,
                                                                std::span<const double> y,
                                                                double confidence,
                                                                int repetitions, uint64_t seed) {
  DCS_RETURN_IF_ERROR(CheckSample(x, "X"));
  DCS_RETURN_IF_ERROR(CheckSample(y, "Y"));
  std::vector<double> x_sample;
  std::vector<double> y_sample;
  return PercentileBootstrap(confidence, repetitions, seed, "improvement", [&](Random& random) {
    x_sample.clear();
    y_sample.clear();
    AppendResample(x, random, x_sample);
    AppendResample(y, random, y_sample);
    return PairwiseImprovement(x_sample, y_sample);
  });
}

}  // namespace dcs::coordinator
