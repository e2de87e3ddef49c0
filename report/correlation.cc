// Copyright 2026 The DCS Authors.
#include "report/correlation.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include <boost/math/distributions/students_t.hpp>

#include "absl/strings/str_cat.h"
#include "report/sample_stats.h"

namespace dcs::report {

absl::StatusOr<Correlation> PearsonCorrelation(std::span<const double> x,
                                               std::span<const double> y) {
  if (x.size() != y.size()) {
    return absl::InvalidArgumentError(
        absl::StrCat("a correlation needs pairs: ", x.size(), " x values, ", y.size(), " y"));
  }
  if (x.size() < 3) {
    return absl::InvalidArgumentError(
        absl::StrCat("a correlation's test needs at least three pairs, got ", x.size()));
  }
  for (std::span<const double> values : {x, y}) {
    if (!std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); })) {
      return absl::InvalidArgumentError("a value to correlate is not finite");
    }
  }
  const double mean_x = Mean(x);
  const double mean_y = Mean(y);
  double sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mean_x) * (y[i] - mean_y);
    sxx += (x[i] - mean_x) * (x[i] - mean_x);
    syy += (y[i] - mean_y) * (y[i] - mean_y);
  }
  if (sxx == 0 || syy == 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(sxx == 0 ? "x" : "y", " is constant: the correlation is undefined"));
  }
  Correlation result{.r = std::clamp(sxy / std::sqrt(sxx * syy), -1.0, 1.0),
                     .n = static_cast<int>(x.size())};
  if (std::abs(result.r) == 1) {
    result.p_value = 0;
    return result;
  }
  const double df = result.n - 2;
  const double t = result.r * std::sqrt(df / (1 - result.r * result.r));
  // Boost.Math throws on domain errors; none is expected here, but none may cross the boundary.
  try {
    const boost::math::students_t distribution(df);
    result.p_value = 2 * boost::math::cdf(boost::math::complement(distribution, std::abs(t)));
  } catch (const std::exception& error) {
    return absl::InternalError(
        absl::StrCat("Student's t tail at t = ", t, " with ", df, " degrees of freedom: ",
                     error.what()));
  }
  return result;
}

}  // namespace dcs::report
