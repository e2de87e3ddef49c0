// Copyright 2026 The DCS Authors.
#include "coordinator/pruners.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "absl/strings/str_cat.h"
#include "coordinator/iqm.h"

namespace dcs::coordinator {
namespace {

// numpy.nanpercentile(values, q): Quantile's rule over the values that are not NaN; NaN if none.
double NanPercentile(std::vector<double> values, double q) {
  std::erase_if(values, [](double v) { return std::isnan(v); });
  if (values.empty()) return std::nan("");
  return Quantile(values, q / 100).value_or(std::nan(""));
}

// Whether `value` is among the best 1/reduction_factor of `competing` (it included).
bool Promotable(double value, std::vector<double> competing, int reduction_factor,
                Direction direction) {
  const size_t k = std::max<size_t>(1, competing.size() / static_cast<size_t>(reduction_factor));
  std::sort(competing.begin(), competing.end());
  return direction == Direction::kMaximize ? value >= competing[competing.size() - k]
                                           : value <= competing[k - 1];
}

}  // namespace

bool MedianPrune(const StudyTrial& trial, const std::vector<StudyTrial>& trials,
                 Direction direction, const MedianPrunerOptions& options) {
  if (trial.reported.empty()) return false;
  std::vector<const StudyTrial*> complete;
  for (const StudyTrial& other : trials) {
    if (other.state == TrialState::kComplete && other.number != trial.number) {
      complete.push_back(&other);
    }
  }
  if (complete.empty() || static_cast<int>(complete.size()) < options.startup_trials) return false;
  const int64_t step = trial.reported.rbegin()->first;
  if (step < options.warmup_steps) return false;
  // Checked once per interval: at the first report at or past its start.
  const int64_t interval_start =
      (step - options.warmup_steps) / options.interval_steps * options.interval_steps +
      options.warmup_steps;
  if (trial.reported.size() >= 2 && std::prev(trial.reported.end(), 2)->first >= interval_start) {
    return false;
  }
  double best = std::nan("");
  for (const auto& [reported_step, value] : trial.reported) {
    if (std::isnan(value)) continue;
    if (std::isnan(best) || IsBetter(direction, value, best)) {
      best = value;
    }
  }
  if (std::isnan(best)) return true;
  std::vector<double> at_step;
  for (const StudyTrial* other : complete) {
    if (const auto value = other->reported.find(step); value != other->reported.end()) {
      at_step.push_back(value->second);
    }
  }
  if (static_cast<int>(at_step.size()) < options.min_trials) return false;
  const double threshold =
      NanPercentile(std::move(at_step), direction == Direction::kMaximize ? 100 - options.percentile
                                                                          : options.percentile);
  if (std::isnan(threshold)) return false;
  return direction == Direction::kMaximize ? best < threshold : best > threshold;
}

HalvingDecision SuccessiveHalvingPrune(const StudyTrial& trial,
                                       const std::map<int, double>& trial_rungs,
                                       const std::vector<std::map<int, double>>& other_rungs,
                                       const std::vector<StudyTrial>& trials, Direction direction,
                                       const SuccessiveHalvingOptions& options) {
  HalvingDecision decision{.rungs = trial_rungs};
  if (trial.reported.empty()) return decision;
  int64_t min_resource = 0;
  if (options.min_resource.has_value()) {
    min_resource = *options.min_resource;
  } else {
    const StudyTrial* first = nullptr;
    for (const StudyTrial& other : trials) {
      if (other.state == TrialState::kComplete && !other.reported.empty() &&
          (first == nullptr || other.number < first->number)) {
        first = &other;
      }
    }
    if (first == nullptr) return decision;
    min_resource = std::max<int64_t>(1, first->reported.rbegin()->first / 100);
  }
  const auto& [step, value] = *trial.reported.rbegin();
  for (int rung = static_cast<int>(trial_rungs.size());; ++rung) {
    const double promotion_step =
        static_cast<double>(min_resource) *
        std::pow(options.reduction_factor, options.min_early_stopping_rate + rung);
    if (static_cast<double>(step) < promotion_step) return decision;
    if (std::isnan(value)) {
      decision.prune = true;
      return decision;
    }
    decision.rungs[rung] = value;
    std::vector<double> competing = {value};
    for (const std::map<int, double>& rungs : other_rungs) {
      if (const auto recorded = rungs.find(rung); recorded != rungs.end()) {
        competing.push_back(recorded->second);
      }
    }
    if (static_cast<int>(competing.size()) <= options.bootstrap_count ||
        !Promotable(value, std::move(competing), options.reduction_factor, direction)) {
      decision.prune = true;
      return decision;
    }
  }
}

absl::Status ValidatePrunerOptions(const PrunerOptions& options) {
  const MedianPrunerOptions& median = options.median;
  const SuccessiveHalvingOptions& halving = options.halving;
  const auto fail = [](absl::string_view what) {
    return absl::InvalidArgumentError(absl::StrCat("pruner option out of range: ", what));
  };
  if (!(median.percentile >= 0 && median.percentile <= 100)) return fail("percentile in [0, 100]");
  if (median.startup_trials < 0) return fail("startup_trials >= 0");
  if (median.warmup_steps < 0) return fail("warmup_steps >= 0");
  if (median.interval_steps < 1) return fail("interval_steps >= 1");
  if (median.min_trials < 1) return fail("min_trials >= 1");
  if (halving.min_resource.has_value() && *halving.min_resource < 1) {
    return fail("min_resource >= 1");
  }
  if (halving.reduction_factor < 2) return fail("reduction_factor >= 2");
  if (halving.min_early_stopping_rate < 0) return fail("min_early_stopping_rate >= 0");
  if (halving.bootstrap_count < 0) return fail("bootstrap_count >= 0");
  return absl::OkStatus();
}

}  // namespace dcs::coordinator
