// Copyright 2026 The DCS Authors.
#include "report/probability_of_improvement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "common/random.h"
#include "common/status_macros.h"

namespace dcs::report {
namespace {

// Resamples treated together by the fast path: the lanes of one pass.
constexpr size_t kBlock = 256;

absl::Status CheckSample(std::span<const double> values, absl::string_view name) {
  if (values.empty()) return absl::InvalidArgumentError(absl::StrCat("no runs in ", name));
  for (double value : values) {
    if (std::isnan(value)) {
      return absl::InvalidArgumentError(absl::StrCat("a run of ", name, " is NaN"));
    }
  }
  return absl::OkStatus();
}

// The improvement from its count of wins in halves (a win counts 2, a tie 1: an exact integer).
double FromHalfWins(double half_wins, size_t x_size, size_t y_size) {
  return half_wins / (2.0 * static_cast<double>(x_size) * static_cast<double>(y_size));
}

// Where each run of X stands among the runs of Y. A drawn run a of X scores
// 2 #{drawn y < a} + #{drawn y = a} = drawn_y(below(a)) + drawn_y(up_to(a)) half wins, with
// drawn_y(k) the number of drawn runs among Y's k smallest: a prefix sum of Y's counts in
// ascending order of value.
struct Ranks {
  Ranks(std::span<const double> x, std::span<const double> y)
      : y_order(y.size()), below(x.size()), up_to(x.size()) {
    std::iota(y_order.begin(), y_order.end(), size_t{0});
    std::sort(y_order.begin(), y_order.end(), [&](size_t a, size_t b) { return y[a] < y[b]; });
    std::vector<double> y_sorted;
    for (const size_t j : y_order) y_sorted.push_back(y[j]);
    for (size_t i = 0; i < x.size(); ++i) {
      below[i] = std::lower_bound(y_sorted.begin(), y_sorted.end(), x[i]) - y_sorted.begin();
      up_to[i] = std::upper_bound(y_sorted.begin(), y_sorted.end(), x[i]) - y_sorted.begin();
    }
  }

  std::vector<size_t> y_order;  // y_order[k]: the index of Y's k-th smallest run
  std::vector<size_t> below;    // per run of X: how many runs of Y are smaller
  std::vector<size_t> up_to;    // per run of X: how many runs of Y are at most as large
};

// The improvement of one resample, from how often each run of X, then of Y, was drawn.
double ImprovementOfResample(std::span<const uint32_t> counts, const Ranks& ranks,
                             std::vector<uint64_t>& drawn_y) {
  const size_t x_size = ranks.below.size();
  const size_t y_size = ranks.y_order.size();
  drawn_y[0] = 0;
  for (size_t k = 0; k < y_size; ++k) {
    drawn_y[k + 1] = drawn_y[k] + counts[x_size + ranks.y_order[k]];
  }
  uint64_t half_wins = 0;
  for (size_t i = 0; i < x_size; ++i) {
    half_wins += counts[i] * (drawn_y[ranks.below[i]] + drawn_y[ranks.up_to[i]]);
  }
  return FromHalfWins(static_cast<double>(half_wins), x_size, y_size);
}

// ImprovementOfResample of every resample of `draws` (at most kMaxLaneValues runs a side),
// kBlock resamples at a time, one lane each.
void LaneImprovements(const coordinator::internal::BootstrapDraws& draws, const Ranks& ranks,
                      std::span<double> estimates) {
  const size_t x_size = ranks.below.size();
  const size_t y_size = ranks.y_order.size();
  std::vector<uint8_t> drawn_y((y_size + 1) * kBlock);  // [k * kBlock + b]: b's drawn_y(k)
  std::array<uint32_t, kBlock> half_wins;
  const auto repetitions = static_cast<size_t>(draws.repetitions());
  for (size_t first = 0; first < repetitions; first += kBlock) {
    const size_t block = std::min(kBlock, repetitions - first);
    std::fill(drawn_y.begin(), drawn_y.begin() + kBlock, 0);
    for (size_t k = 0; k < y_size; ++k) {
      const uint8_t* counts = draws.counts_of(x_size + ranks.y_order[k]).data() + first;
      const uint8_t* from = &drawn_y[k * kBlock];
      uint8_t* to = &drawn_y[(k + 1) * kBlock];
      for (size_t b = 0; b < block; ++b) to[b] = from[b] + counts[b];
    }
    half_wins.fill(0);
    for (size_t i = 0; i < x_size; ++i) {
      const uint8_t* counts = draws.counts_of(i).data() + first;
      const uint8_t* below = &drawn_y[ranks.below[i] * kBlock];
      const uint8_t* up_to = &drawn_y[ranks.up_to[i] * kBlock];
      for (size_t b = 0; b < block; ++b) {
        half_wins[b] += uint32_t{counts[b]} * (uint32_t{below[b]} + uint32_t{up_to[b]});
      }
    }
    for (size_t b = 0; b < block; ++b) {
      estimates[first + b] = FromHalfWins(half_wins[b], x_size, y_size);
    }
  }
}

}  // namespace

absl::StatusOr<double> ProbabilityOfImprovement(std::span<const double> x,
                                                std::span<const double> y) {
  DCS_RETURN_IF_ERROR(CheckSample(x, "X"));
  DCS_RETURN_IF_ERROR(CheckSample(y, "Y"));
  double half_wins = 0;
  for (double a : x) {
    for (double b : y) half_wins += a > b ? 2 : (a == b ? 1 : 0);
  }
  return FromHalfWins(half_wins, x.size(), y.size());
}

absl::StatusOr<coordinator::ConfidenceInterval> BootstrapImprovementInterval(
    std::span<const double> x, std::span<const double> y, double confidence, int repetitions,
    uint64_t seed) {
  DCS_RETURN_IF_ERROR(CheckSample(x, "X"));
  DCS_RETURN_IF_ERROR(CheckSample(y, "Y"));
  DCS_RETURN_IF_ERROR(coordinator::internal::CheckBootstrap(confidence, repetitions));
  const size_t sizes[] = {x.size(), y.size()};
  const Ranks ranks(x, y);
  std::vector<double> estimates(repetitions);
  if (std::max(x.size(), y.size()) <= coordinator::internal::kMaxLaneValues) {
    LaneImprovements(
        *coordinator::internal::BootstrapDraws::Shared(sizes, repetitions, seed, "improvement"),
        ranks, estimates);
  } else {  // the same draws, one resample at a time
    Random random(StreamSeed(seed, "improvement"));
    std::vector<uint32_t> counts(x.size() + y.size());
    std::vector<uint64_t> drawn_y(y.size() + 1);
    for (double& estimate : estimates) {
      std::fill(counts.begin(), counts.end(), 0);
      coordinator::internal::DrawResample(sizes, random, [&](size_t i) { ++counts[i]; });
      estimate = ImprovementOfResample(counts, ranks, drawn_y);
    }
  }
  return coordinator::internal::PercentileInterval(estimates, confidence);
}

}  // namespace dcs::report
