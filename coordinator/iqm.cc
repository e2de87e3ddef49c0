// Copyright 2026 The DCS Authors.
#include "coordinator/iqm.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "common/random.h"
#include "common/status_macros.h"

namespace dcs::coordinator {
namespace {

absl::Status CheckValues(std::span<const double> values) {
  if (values.empty()) return absl::InvalidArgumentError("no values to summarise");
  for (double value : values) {
    if (std::isnan(value)) return absl::InvalidArgumentError("a value to summarise is NaN");
  }
  return absl::OkStatus();
}

double TrimmedMeanOfSorted(const std::vector<double>& sorted) {
  const size_t cut = sorted.size() / 4;
  double sum = 0;
  for (size_t i = cut; i < sorted.size() - cut; ++i) sum += sorted[i];
  return sum / static_cast<double>(sorted.size() - 2 * cut);
}

double QuantileOfSorted(const std::vector<double>& sorted, double q) {
  const double position = static_cast<double>(sorted.size() - 1) * q;
  const size_t below = static_cast<size_t>(std::floor(position));
  const size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

std::vector<double> Sorted(std::span<const double> values) {
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

}  // namespace

absl::StatusOr<double> InterquartileMean(std::span<const double> values) {
  DCS_RETURN_IF_ERROR(CheckValues(values));
  return TrimmedMeanOfSorted(Sorted(values));
}

absl::StatusOr<double> Quantile(std::span<const double> values, double q) {
  DCS_RETURN_IF_ERROR(CheckValues(values));
  if (!(q >= 0 && q <= 1)) {
    return absl::InvalidArgumentError(absl::StrCat("a quantile must be in [0, 1], got ", q));
  }
  return QuantileOfSorted(Sorted(values), q);
}

absl::StatusOr<IqmSummary> SummarizeIqm(std::span<const double> values) {
  DCS_RETURN_IF_ERROR(CheckValues(values));
  const std::vector<double> sorted = Sorted(values);
  return IqmSummary{.iqm = TrimmedMeanOfSorted(sorted),
                    .q1 = QuantileOfSorted(sorted, 0.25),
                    .q3 = QuantileOfSorted(sorted, 0.75)};
}

absl::StatusOr<ConfidenceInterval> PercentileBootstrap(
    double confidence, int repetitions, uint64_t seed, absl::string_view stream,
    absl::FunctionRef<double(Random& random)> estimate) {
  if (!(confidence > 0 && confidence < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("confidence must be in (0, 1), got ", confidence));
  }
  if (repetitions < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("bootstrap repetitions must be at least 1, got ", repetitions));
  }
  Random random(StreamSeed(seed, stream));
  std::vector<double> estimates;
  estimates.reserve(repetitions);
  for (int r = 0; r < repetitions; ++r) estimates.push_back(estimate(random));
  std::sort(estimates.begin(), estimates.end());
  const double tail = (1 - confidence) / 2;
  return ConfidenceInterval{.lo = QuantileOfSorted(estimates, tail),
                            .hi = QuantileOfSorted(estimates, 1 - tail)};
}

void AppendResample(std::span<const double> from, Random& random, std::vector<double>& to) {
  const auto size = static_cast<int64_t>(from.size());
  for (int64_t i = 0; i < size; ++i) to.push_back(from[random.Integers(0, size)]);
}

absl::StatusOr<ConfidenceInterval> BootstrapIqmInterval(
    const std::vector<std::vector<double>>& strata, double confidence, int repetitions,
    uint64_t seed) {
  if (strata.empty()) return absl::InvalidArgumentError("no strata to bootstrap");
  for (const std::vector<double>& stratum : strata) DCS_RETURN_IF_ERROR(CheckValues(stratum));
  std::vector<double> sample;
  return PercentileBootstrap(confidence, repetitions, seed, "bootstrap", [&](Random& random) {
    sample.clear();
    for (const std::vector<double>& stratum : strata) AppendResample(stratum, random, sample);
    std::sort(sample.begin(), sample.end());
    return TrimmedMeanOfSorted(sample);
  });
}

}  // namespace dcs::coordinator
