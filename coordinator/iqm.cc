// Copyright 2026 The DCS Authors.
#include "coordinator/iqm.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "common/random.h"
#include "common/status_macros.h"

namespace dcs::coordinator {
namespace {

// Resamples treated together by the fast path: the byte lanes of one pass.
constexpr size_t kBlock = 256;

// PercentileInterval samples every kSampleStep-th estimate to find thresholds that cut off the
// interval's tails; below kMinSampled estimates it selects among all of them directly.
constexpr size_t kSampleStep = 32;
constexpr size_t kMinSampled = 8 * kSampleStep;

// What BootstrapDraws::Shared keeps.
struct DrawsCache {
  absl::Mutex mu;
  std::vector<std::shared_ptr<const internal::BootstrapDraws>> kept ABSL_GUARDED_BY(mu);
};

absl::Status CheckValues(std::span<const double> values) {
  if (values.empty()) return absl::InvalidArgumentError("no values to summarise");
  for (double value : values) {
    if (std::isnan(value)) return absl::InvalidArgumentError("a value to summarise is NaN");
  }
  return absl::OkStatus();
}

double TrimmedMeanOfSorted(std::span<const double> sorted) {
  const size_t cut = sorted.size() / 4;
  double sum = 0;
  for (size_t i = cut; i < sorted.size() - cut; ++i) sum += sorted[i];
  return sum / static_cast<double>(sorted.size() - 2 * cut);
}

// Quantile's rule: position (n - 1) q, between the order statistics below and above it.
struct QuantilePosition {
  QuantilePosition(size_t n, double q)
      : position(static_cast<double>(n - 1) * q),
        below(static_cast<size_t>(std::floor(position))),
        above(std::min(below + 1, n - 1)) {}

  double Interpolate(double at_below, double at_above) const {
    return at_below + (position - static_cast<double>(below)) * (at_above - at_below);
  }

  double position;
  size_t below;
  size_t above;
};

double QuantileOfSorted(std::span<const double> sorted, double q) {
  const QuantilePosition at(sorted.size(), q);
  return at.Interpolate(sorted[at.below], sorted[at.above]);
}

std::vector<double> Sorted(std::span<const double> values) {
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

// Values in ascending order, and where each came from.
struct Ranked {
  explicit Ranked(std::span<const double> values) : order(values.size()) {
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return values[a] < values[b]; });
    for (const size_t i : order) sorted.push_back(values[i]);
  }

  std::vector<size_t> order;  // order[k]: the index of the k-th smallest value
  std::vector<double> sorted;
};

// The IQM of one resample, from how often each value was drawn (`counts`): the middle of the
// sorted resample, added in ascending order as TrimmedMeanOfSorted adds it (the same bits).
double TrimmedMeanOfResample(std::span<const uint32_t> counts, const Ranked& values) {
  const size_t cut = values.sorted.size() / 4;
  const size_t kept = values.sorted.size() - 2 * cut;
  size_t skip = cut;
  size_t take = kept;
  double sum = 0;
  for (size_t k = 0; take > 0; ++k) {
    size_t count = counts[values.order[k]];
    const size_t skipped = std::min(count, skip);
    skip -= skipped;
    count = std::min(count - skipped, take);
    take -= count;
    for (; count > 0; --count) sum += values.sorted[k];
  }
  return sum / static_cast<double>(kept);
}

// TrimmedMeanOfResample of every resample of `draws` (at most kMaxLaneValues values), kBlock
// resamples at a time, one byte lane each. Position q of a sorted resample holds the value of
// rank #{k : end_k <= q}, end_k the number of drawn values of rank k or less; the middle
// positions' values are then added in ascending order, as there.
void LaneTrimmedMeans(const internal::BootstrapDraws& draws, const Ranked& values,
                      std::span<double> estimates) {
  const size_t n = values.sorted.size();
  const size_t cut = n / 4;
  const size_t kept = n - 2 * cut;
  std::array<uint8_t, kBlock> end;
  std::vector<uint8_t> rank(kept * kBlock);  // [p * kBlock + b]: position cut + p's, of b
  const auto repetitions = static_cast<size_t>(draws.repetitions());
  for (size_t first = 0; first < repetitions; first += kBlock) {
    const size_t block = std::min(kBlock, repetitions - first);
    end.fill(0);
    std::fill(rank.begin(), rank.end(), 0);
    for (size_t k = 0; k + 1 < n; ++k) {  // the largest rank ends at n, past every position
      const uint8_t* counts = draws.counts_of(values.order[k]).data() + first;
      for (size_t b = 0; b < block; ++b) end[b] += counts[b];
      for (size_t p = 0; p < kept; ++p) {
        uint8_t* ranks = &rank[p * kBlock];
        const auto q = static_cast<uint8_t>(cut + p);
        for (size_t b = 0; b < block; ++b) ranks[b] += end[b] <= q;
      }
    }
    for (size_t b = 0; b < block; ++b) {
      double sum = 0;
      for (size_t p = 0; p < kept; ++p) sum += values.sorted[rank[p * kBlock + b]];
      estimates[first + b] = sum / static_cast<double>(kept);
    }
  }
}

// The sample rank, among `sample_size` values sampled from `size`, below which a value of
// rank `rank` falls with high probability: its expected sample rank, about binomial, plus four
// of its standard deviations (at most the square root of the expectation) and one.
double SampleRankAbove(size_t rank, size_t size, size_t sample_size) {
  const double expected =
      static_cast<double>(rank + 1) * static_cast<double>(sample_size) / static_cast<double>(size);
  return expected + 4 * std::sqrt(expected) + 1;
}

// The quantile at `at` of estimates of which `values` holds the `first` smallest but none, and
// then all up to rank at.above at least: the order statistics at at.below (std::nth_element's
// pick) and at.above (the next larger value), interpolated. Reorders `values`.
double SelectQuantile(std::span<double> values, size_t first, const QuantilePosition& at) {
  const auto below = values.begin() + static_cast<ptrdiff_t>(at.below - first);
  std::nth_element(values.begin(), below, values.end());
  const double at_above =
      at.above == at.below ? *below : *std::min_element(below + 1, values.end());
  return at.Interpolate(*below, at_above);
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

std::optional<HighestIqmGroup> HighestIqm(const std::vector<std::vector<double>>& groups) {
  std::optional<HighestIqmGroup> highest;
  for (size_t i = 0; i < groups.size(); ++i) {
    if (groups[i].empty()) continue;
    const absl::StatusOr<double> iqm = InterquartileMean(groups[i]);
    if (iqm.ok() && (!highest.has_value() || *iqm > highest->iqm)) highest = {i, *iqm};
  }
  return highest;
}

absl::StatusOr<ConfidenceInterval> BootstrapIqmInterval(
    const std::vector<std::vector<double>>& strata, double confidence, int repetitions,
    uint64_t seed) {
  if (strata.empty()) return absl::InvalidArgumentError("no strata to bootstrap");
  for (const std::vector<double>& stratum : strata) DCS_RETURN_IF_ERROR(CheckValues(stratum));
  DCS_RETURN_IF_ERROR(internal::CheckBootstrap(confidence, repetitions));
  std::vector<size_t> sizes;
  std::vector<double> all;
  for (const std::vector<double>& stratum : strata) {
    sizes.push_back(stratum.size());
    all.insert(all.end(), stratum.begin(), stratum.end());
  }
  const Ranked values(all);
  std::vector<double> estimates(repetitions);
  if (all.size() <= internal::kMaxLaneValues) {
    LaneTrimmedMeans(*internal::BootstrapDraws::Shared(sizes, repetitions, seed, "bootstrap"),
                     values, estimates);
  } else {  // the same draws, one resample at a time
    Random random(StreamSeed(seed, "bootstrap"));
    std::vector<uint32_t> counts(all.size());
    for (double& estimate : estimates) {
      std::fill(counts.begin(), counts.end(), 0);
      internal::DrawResample(sizes, random, [&](size_t i) { ++counts[i]; });
      estimate = TrimmedMeanOfResample(counts, values);
    }
  }
  return internal::PercentileInterval(estimates, confidence);
}

namespace internal {

BootstrapDraws::BootstrapDraws(std::span<const size_t> sizes, int repetitions, uint64_t seed,
                               absl::string_view stream)
    : sizes_(sizes.begin(), sizes.end()),
      repetitions_(repetitions),
      seed_(seed),
      stream_(stream),
      counts_(std::accumulate(sizes.begin(), sizes.end(), size_t{0}) *
              static_cast<size_t>(repetitions)) {
  Random random(StreamSeed(seed, stream));
  const auto stride = static_cast<size_t>(repetitions);
  for (size_t r = 0; r < stride; ++r) {
    DrawResample(sizes, random, [&](size_t i) { ++counts_[i * stride + r]; });
  }
}

std::shared_ptr<const BootstrapDraws> BootstrapDraws::Shared(std::span<const size_t> sizes,
                                                             int repetitions, uint64_t seed,
                                                             absl::string_view stream) {
  // Never destroyed: freeing its draws at exit would cost glibc a consolidation of every small
  // block the process freed before (about 4 ms after a report).
  static DrawsCache& cache = *new DrawsCache;
  const auto find = [&]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(cache.mu) {
    // The latest is kept last.
    for (auto it = cache.kept.begin(); it != cache.kept.end(); ++it) {
      if ((*it)->Matches(sizes, repetitions, seed, stream)) {
        std::rotate(it, it + 1, cache.kept.end());
        return cache.kept.back();
      }
    }
    return std::shared_ptr<const BootstrapDraws>();
  };
  {
    absl::MutexLock lock(&cache.mu);
    if (auto draws = find()) return draws;
  }
  auto draws = std::make_shared<const BootstrapDraws>(sizes, repetitions, seed, stream);
  absl::MutexLock lock(&cache.mu);
  if (auto drawn_meanwhile = find()) return drawn_meanwhile;
  if (cache.kept.size() == kKept) cache.kept.erase(cache.kept.begin());
  cache.kept.push_back(draws);
  return draws;
}

bool BootstrapDraws::Matches(std::span<const size_t> sizes, int repetitions, uint64_t seed,
                             absl::string_view stream) const {
  return std::equal(sizes.begin(), sizes.end(), sizes_.begin(), sizes_.end()) &&
         repetitions == repetitions_ && seed == seed_ && stream == stream_;
}

absl::Status CheckBootstrap(double confidence, int repetitions) {
  if (!(confidence > 0 && confidence < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("confidence must be in (0, 1), got ", confidence));
  }
  if (repetitions < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("bootstrap repetitions must be at least 1, got ", repetitions));
  }
  return absl::OkStatus();
}

ConfidenceInterval PercentileInterval(std::span<double> estimates, double confidence) {
  const size_t n = estimates.size();
  const double tail = (1 - confidence) / 2;
  const QuantilePosition lo(n, tail);
  const QuantilePosition hi(n, 1 - tail);
  if (n >= kMinSampled) {
    // A sample of every kSampleStep-th estimate gives two thresholds: `low` below which the two
    // order statistics of `lo` fall, and `high` above which those of `hi` do, each with high
    // probability. One pass gathers the estimates at most `low`, the smallest ones, and those
    // at least `high`, the largest; selection among them reads the same order statistics.
    std::vector<double> sample;
    for (size_t i = kSampleStep / 2; i < n; i += kSampleStep) sample.push_back(estimates[i]);
    const size_t m = sample.size();
    const size_t low_rank = std::min(m - 1, static_cast<size_t>(SampleRankAbove(lo.above, n, m)));
    const size_t high_rank =
        m - 1 - std::min(m - 1, static_cast<size_t>(SampleRankAbove(n - 1 - hi.below, n, m)));
    std::nth_element(sample.begin(), sample.begin() + low_rank, sample.end());
    const double low = sample[low_rank];
    std::nth_element(sample.begin(), sample.begin() + high_rank, sample.end());
    const double high = sample[high_rank];
    std::vector<double> smallest;
    std::vector<double> largest;
    for (const double estimate : estimates) {
      if (estimate <= low) smallest.push_back(estimate);
      if (estimate >= high) largest.push_back(estimate);
    }
    const size_t below_largest = n - largest.size();
    if (lo.above < smallest.size() && hi.below >= below_largest) {
      return ConfidenceInterval{.lo = SelectQuantile(smallest, 0, lo),
                                .hi = SelectQuantile(largest, below_largest, hi)};
    }
  }
  return ConfidenceInterval{.lo = SelectQuantile(estimates, 0, lo),
                            .hi = SelectQuantile(estimates, 0, hi)};
}

}  // namespace internal
}  // namespace dcs::coordinator
