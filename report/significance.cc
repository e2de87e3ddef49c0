// Copyright 2026 The DCS Authors.
#include "report/significance.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numeric>
#include <utility>

#include <boost/math/distributions/normal.hpp>

#include "absl/strings/str_cat.h"

namespace dcs::report {

absl::StatusOr<MannWhitney> MannWhitneyTest(std::span<const double> x, std::span<const double> y) {
  if (x.empty() || y.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "a Mann-Whitney test needs runs on both sides, got ", x.size(), " and ", y.size()));
  }
  // The pooled values with their side (true: x), sorted; ties get the mean of their ranks.
  std::vector<std::pair<double, bool>> pooled;
  for (const auto& [values, is_x] : {std::pair{x, true}, std::pair{y, false}}) {
    for (const double value : values) {
      if (!std::isfinite(value)) {
        return absl::InvalidArgumentError(
            absl::StrCat("a Mann-Whitney test needs finite values, got ", value));
      }
      pooled.emplace_back(value, is_x);
    }
  }
  std::sort(pooled.begin(), pooled.end());
  double rank_sum_x = 0;
  double tie_term = 0;  // sum over tie groups of t^3 - t
  for (size_t first = 0; first < pooled.size();) {
    size_t end = first;
    while (end < pooled.size() && pooled[end].first == pooled[first].first) ++end;
    const double ties = static_cast<double>(end - first);
    const double rank = (static_cast<double>(first + 1) + static_cast<double>(end)) / 2;
    for (size_t i = first; i < end; ++i) rank_sum_x += pooled[i].second ? rank : 0;
    tie_term += ties * ties * ties - ties;
    first = end;
  }
  const double n_x = static_cast<double>(x.size());
  const double n_y = static_cast<double>(y.size());
  const double n = n_x + n_y;
  MannWhitney result{.u = rank_sum_x - n_x * (n_x + 1) / 2};
  const double mean = n_x * n_y / 2;
  const double sd = std::sqrt(n_x * n_y / 12 * ((n + 1) - tie_term / (n * (n - 1))));
  if (!(sd > 0)) return result;  // every value ties: no evidence either way
  const double u_max = std::max(result.u, n_x * n_y - result.u);
  result.z = (u_max - mean - 0.5) / sd;
  try {
    const boost::math::normal normal;
    result.p_value = std::min(1.0, 2 * boost::math::cdf(boost::math::complement(normal, result.z)));
  } catch (const std::exception& error) {
    return absl::InternalError(
        absl::StrCat("the normal tail at z = ", result.z, ": ", error.what()));
  }
  return result;
}

absl::StatusOr<std::vector<double>> HolmAdjusted(std::span<const double> p_values) {
  for (const double p : p_values) {
    if (!(p >= 0 && p <= 1)) {
      return absl::InvalidArgumentError(absl::StrCat("a p-value must be in [0, 1], got ", p));
    }
  }
  std::vector<size_t> order(p_values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return p_values[a] < p_values[b]; });
  std::vector<double> adjusted(p_values.size());
  double running = 0;  // the step-down's maximum so far
  for (size_t i = 0; i < order.size(); ++i) {
    const double factor = static_cast<double>(order.size() - i);
    running = std::max(running, std::min(1.0, factor * p_values[order[i]]));
    adjusted[order[i]] = running;
  }
  return adjusted;
}

}  // namespace dcs::report
