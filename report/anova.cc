// Copyright 2026 The DCS Authors.
#include "report/anova.h"

#include <cmath>
#include <exception>
#include <limits>

#include <boost/math/distributions/fisher_f.hpp>

#include "absl/strings/str_cat.h"
#include "report/sample_stats.h"

namespace dcs::report {
namespace {

absl::Status CheckGroups(const std::vector<std::vector<double>>& groups) {
  if (groups.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrCat("a one-way ANOVA needs at least two groups, got ", groups.size()));
  }
  size_t total = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) {
      return absl::InvalidArgumentError(absl::StrCat("ANOVA group ", g, " has no values"));
    }
    for (double value : groups[g]) {
      if (!std::isfinite(value)) {
        return absl::InvalidArgumentError(
            absl::StrCat("ANOVA group ", g, " holds a value that is not finite: ", value));
      }
    }
    total += groups[g].size();
  }
  if (total == groups.size()) {
    return absl::InvalidArgumentError(
        "every ANOVA group has one value: no variance within groups (N - k = 0)");
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<AnovaResult> OneWayAnova(const std::vector<std::vector<double>>& groups) {
  if (absl::Status checked = CheckGroups(groups); !checked.ok()) return checked;
  std::vector<double> all;
  for (const std::vector<double>& group : groups) all.insert(all.end(), group.begin(), group.end());
  const double grand_mean = Mean(all);
  double between = 0;  // SSB
  double within = 0;   // SSW
  for (const std::vector<double>& group : groups) {
    const double mean = Mean(group);
    between += static_cast<double>(group.size()) * (mean - grand_mean) * (mean - grand_mean);
    for (double value : group) within += (value - mean) * (value - mean);
  }
  AnovaResult result;
  result.df_between = static_cast<int>(groups.size()) - 1;
  result.df_within = static_cast<int>(all.size() - groups.size());
  if (within == 0) {
    if (between == 0) {
      return absl::InvalidArgumentError("every ANOVA value is equal: F is undefined (0/0)");
    }
    result.f = std::numeric_limits<double>::infinity();
    result.p_value = 0;
    return result;
  }
  result.f = (between / result.df_between) / (within / result.df_within);
  // Boost.Math reports domain and evaluation errors by throwing; none is expected for a finite
  // F >= 0 and positive degrees of freedom, but none may cross the library boundary either.
  try {
    const boost::math::fisher_f distribution(result.df_between, result.df_within);
    result.p_value = boost::math::cdf(boost::math::complement(distribution, result.f));
  } catch (const std::exception& error) {
    return absl::InternalError(absl::StrCat("the F distribution's tail at F = ", result.f,
                                            " with (", result.df_between, ", ",
                                            result.df_within, ") degrees of freedom: ",
                                            error.what()));
  }
  return result;
}

}  // namespace dcs::report
