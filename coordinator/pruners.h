// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_PRUNERS_H_
#define DCS_COORDINATOR_PRUNERS_H_

// Pruners decide, when a trial reports an intermediate value (for a multi-stage schedule, its
// objective at a stage boundary), whether to stop it early, with Optuna 4.9's rules
// (Optuna 4.9's optuna/pruners/). Pure functions of the study's trials: what a pruner must remember
// (the rungs each trial reached in successive halving) is passed in and returned, and the caller
// stores it. Thread-safe.

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "absl/status/status.h"
#include "common/enum_names.h"
#include "coordinator/sampler.h"

namespace dcs::coordinator {

// MedianPruner, that is PercentilePruner(50): after `startup_trials` trials completed and past
// `warmup_steps`, at most once per `interval_steps`, prune a trial whose best value so far is
// worse than the median of the complete trials' values at the same step (at least `min_trials`
// of them reported it).
struct MedianPrunerOptions {
  double percentile = 50;  // PercentilePruner's; 50 is the median
  int startup_trials = 5;
  int64_t warmup_steps = 0;
  int64_t interval_steps = 1;
  int min_trials = 1;
};

// Whether `trial` (running, its reports so far; its highest step the one being checked) is
// pruned, given the study's `trials` (only complete ones are compared with).
bool MedianPrune(const StudyTrial& trial, const std::vector<StudyTrial>& trials,
                 Direction direction, const MedianPrunerOptions& options);

// SuccessiveHalvingPruner (asynchronous successive halving): rung r is reached at step
// min_resource · reduction_factor^(min_early_stopping_rate + r); a trial that reaches it records
// its value there and goes on only if that value is among the best 1/reduction_factor of every
// value recorded at rung r so far (and there are more than `bootstrap_count` of them).
struct SuccessiveHalvingOptions {
  // Absent, Optuna's "auto": max(1, last step of a complete trial / 100); no trial is pruned before
  // one completed. Optuna takes the trials complete at its first check; DCS the lowest-numbered
  // complete trial (the first to complete in a sequential study), so that the value does not
  // depend on when checks happen.
  std::optional<int64_t> min_resource;
  int reduction_factor = 4;
  int min_early_stopping_rate = 0;
  int bootstrap_count = 0;
};

struct HalvingDecision {
  bool prune = false;
  // The trial's rungs after the check: rung -> the value recorded there, to be stored with it.
  std::map<int, double> rungs;
};

// The check when `trial` (running) reports at its highest step: `trial_rungs` are the rungs it
// reached so far, `other_rungs` those of every other trial (any state), `trials` the study's (for
// the automatic min_resource). REQUIRES: reduction_factor >= 2.
HalvingDecision SuccessiveHalvingPrune(const StudyTrial& trial,
                                       const std::map<int, double>& trial_rungs,
                                       const std::vector<std::map<int, double>>& other_rungs,
                                       const std::vector<StudyTrial>& trials, Direction direction,
                                       const SuccessiveHalvingOptions& options);

// A study's pruner: none (the default), or one of the two above with its options.
enum class PrunerKind { kNone, kMedian, kSuccessiveHalving };
inline constexpr EnumName<PrunerKind> kPrunerKindNames[] = {
    {PrunerKind::kNone, "none"},
    {PrunerKind::kMedian, "median"},
    {PrunerKind::kSuccessiveHalving, "successive_halving"}};
static_assert(InEnumOrder(kPrunerKindNames));

struct PrunerOptions {
  PrunerKind kind = PrunerKind::kNone;
  MedianPrunerOptions median;
  SuccessiveHalvingOptions halving;
};

// INVALID_ARGUMENT naming the option for options out of range (a percentile outside [0, 100],
// a negative count or step, an interval or min_resource below 1, a reduction factor below 2).
absl::Status ValidatePrunerOptions(const PrunerOptions& options);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_PRUNERS_H_
