// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_IQM_H_
#define DCS_COORDINATOR_IQM_H_

// The paper's across-seed statistics (docs/reference.md, "Scores"), after Agarwal et al. (2021):
// the interquartile mean (IQM) with the first and third quartiles, "IQM [Q1, Q3]", and a
// stratified bootstrap confidence interval for the IQM. Thread-safe: pure functions, but for a
// process-wide cache of bootstrap draws (internal::BootstrapDraws::Shared).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "common/random.h"

namespace dcs::coordinator {

// The 25% trimmed mean, as rliable and scipy.stats.trim_mean(x, 0.25) compute it: sort, drop
// floor(n / 4) values from each end, average the rest (10 seeds: the middle 6; 8: the middle
// 4; 5: the middle 3). INVALID_ARGUMENT if `values` is empty or holds a NaN.
absl::StatusOr<double> InterquartileMean(std::span<const double> values);

// The q-th quantile (0 <= q <= 1) with linear interpolation between order statistics, numpy's
// default: position (n - 1) * q. INVALID_ARGUMENT as above, or for q outside [0, 1].
absl::StatusOr<double> Quantile(std::span<const double> values, double q);

struct IqmSummary {
  double iqm = 0;
  double q1 = 0;
  double q3 = 0;
};

// IQM [Q1, Q3] of `values`. Errors as InterquartileMean.
absl::StatusOr<IqmSummary> SummarizeIqm(std::span<const double> values);

// Of several groups' values (a sweep's trials, each with its completed runs' last
// avg_combined), the group with the highest IQM, the first of equals; a group without values
// or whose IQM fails (a NaN) is passed over. nullopt if none is left. How `dcs watch` and the
// coordinator's metrics name a sweep's best condition so far.
struct HighestIqmGroup {
  size_t index = 0;
  double iqm = 0;
};
std::optional<HighestIqmGroup> HighestIqm(const std::vector<std::vector<double>>& groups);

struct ConfidenceInterval {
  double lo = 0;
  double hi = 0;
};

// A percentile bootstrap interval for the IQM of all values together, resampling with
// replacement within each stratum (rliable's StratifiedBootstrap: a stratum is a task, its
// values the runs on it; one stratum is a plain bootstrap over seeds). `confidence` is e.g.
// 0.95; `repetitions` resamples drawn as internal::DrawResample says from StreamSeed(seed,
// "bootstrap"); the interval is their IQMs' (1 - confidence) / 2 and 1 - (1 - confidence) / 2
// quantiles by Quantile's rule, the same bits as sorting every resample and every IQM would
// give. Up to internal::kMaxLaneValues values, calls with equal stratum sizes, repetitions and
// seed (a report's cells) share one drawing of their resamples (internal::BootstrapDraws).
// INVALID_ARGUMENT for an empty stratum, NaN, confidence outside (0, 1) or repetitions < 1.
absl::StatusOr<ConfidenceInterval> BootstrapIqmInterval(
    const std::vector<std::vector<double>>& strata, double confidence, int repetitions,
    uint64_t seed);

namespace internal {

// The building blocks of BootstrapIqmInterval and BootstrapImprovementInterval
// (report/probability_of_improvement.h).

// Draws one resample of strata of the given sizes: stratum after stratum, as many values as the
// stratum holds, with replacement, one random.Integers(0, size) each (a stratum of one value
// draws nothing); calls count(i) for each drawn value, i its index among the strata's values
// concatenated in order.
template <typename Count>
void DrawResample(std::span<const size_t> sizes, Random& random, Count&& count) {
  size_t first = 0;
  for (const size_t size : sizes) {
    const auto range = static_cast<int64_t>(size);
    for (size_t i = 0; i < size; ++i) count(first + static_cast<size_t>(random.Integers(0, range)));
    first += size;
  }
}

// Strata (or samples) of at most this many values take the fast path: their draws are counted
// in bytes, one byte lane per resample, so that vector instructions treat 16 resamples at once.
inline constexpr size_t kMaxLaneValues = 255;

// `repetitions` resamples drawn by DrawResample from StreamSeed(seed, stream), kept as how often
// each value was drawn in each. Thread-safe: immutable once built.
class BootstrapDraws {
 public:
  // REQUIRES: every size in [1, kMaxLaneValues]; repetitions >= 1.
  BootstrapDraws(std::span<const size_t> sizes, int repetitions, uint64_t seed,
                 absl::string_view stream);

  // The draws of these arguments, built on the first call and kept: the process keeps the last
  // kKept asked for (repetitions bytes per value each: 200 KB for a report's improvements), so
  // the cells of a report, which share their shape and stream, draw once. The caller co-owns
  // them with the cache, which is never destroyed. Thread-safe. REQUIRES: as the constructor.
  static std::shared_ptr<const BootstrapDraws> Shared(std::span<const size_t> sizes,
                                                      int repetitions, uint64_t seed,
                                                      absl::string_view stream);

  int repetitions() const { return repetitions_; }

  // How often value `i` (strata concatenated in order) was drawn: element r for resample r.
  std::span<const uint8_t> counts_of(size_t i) const {
    return std::span<const uint8_t>(counts_).subspan(i * static_cast<size_t>(repetitions_),
                                                     static_cast<size_t>(repetitions_));
  }

 private:
  static constexpr size_t kKept = 2;  // e.g. a report's 10-seed cells and one with 9 runs

  bool Matches(std::span<const size_t> sizes, int repetitions, uint64_t seed,
               absl::string_view stream) const;

  std::vector<size_t> sizes_;
  int repetitions_;
  uint64_t seed_;
  std::string stream_;
  std::vector<uint8_t> counts_;  // value after value, `repetitions_` counts each
};

// INVALID_ARGUMENT for confidence outside (0, 1) or repetitions < 1.
absl::Status CheckBootstrap(double confidence, int repetitions);

// The percentile interval of bootstrap estimates: their (1 - confidence) / 2 and
// 1 - (1 - confidence) / 2 quantiles by Quantile's rule, the same numbers as sorting them would
// give, found by selection. May reorder `estimates`. REQUIRES: non-empty, no NaN; confidence in
// (0, 1).
ConfidenceInterval PercentileInterval(std::span<double> estimates, double confidence);

}  // namespace internal
}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_IQM_H_
