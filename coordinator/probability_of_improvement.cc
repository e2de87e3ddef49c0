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

void Resample(std::span<const double> from, Random& random, std::vector<double>& to) {
  const auto size = static_cast<int64_t>(from.size());
  to.clear();
  for (int64_t i = 0; i < size; ++i) to.push_back(from[random.Integers(0, size)]);
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
  if (!(confidence > 0 && confidence < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("confidence must be in (0, 1), got ", confidence));
  }
  if (repetitions < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("bootstrap repetitions must be at least 1, got ", repetitions));
  }
  Random random(StreamSeed(seed, "improvement"));
  std::vector<double> estimates;
  estimates.reserve(repetitions);
  std::vector<double> x_sample;
  std::vector<double> y_sample;
  for (int r = 0; r < repetitions; ++r) {
    Resample(x, random, x_sample);
    Resample(y, random, y_sample);
    estimates.push_back(PairwiseImprovement(x_sample, y_sample));
  }
  std::sort(estimates.begin(), estimates.end());
  const double tail = (1 - confidence) / 2;
  // The same percentile rule as BootstrapIqmInterval (numpy's linear interpolation).
  DCS_ASSIGN_OR_RETURN(const double lo, Quantile(estimates, tail));
  DCS_ASSIGN_OR_RETURN(const double hi, Quantile(estimates, 1 - tail));
  return ConfidenceInterval{.lo = lo, .hi = hi};
}

}  // namespace dcs::coordinator
