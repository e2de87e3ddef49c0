// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_TPE_SAMPLER_H_
#define DCS_COORDINATOR_TPE_SAMPLER_H_

// The Tree-structured Parzen Estimator, with Optuna 4.9's semantics and defaults
// (optuna/samplers/_tpe/sampler.py): random trials until `startup_trials` have finished; then the
// finished trials split into the best gamma(n) ("below") and the rest ("above"), a Parzen estimator
// is fitted to each, `ei_candidates` candidates are drawn from the below one, and the first that
// maximises ln l(x) - ln g(x) is taken.
//
// Conditional spaces: by default each parameter is sampled on its own (independent TPE), its
// estimators fitted to the trials that have it, so a sinusoid's period is learned only from the
// trials where its stage was sinusoidal. With `multivariate`, parameters are sampled jointly: the
// parameters every finished trial has, or with `group` each group of parameters that always occur
// together; the rest independently. With `constant_liar`, other running trials join the "above"
// set, so that trials in parallel spread out.

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "coordinator/parzen_estimator.h"
#include "coordinator/sampler.h"

namespace dcs::coordinator {

struct TpeOptions {
  int startup_trials = 10;
  int ei_candidates = 24;
  ParzenOptions parzen;  // parzen.multivariate: joint sampling (Scott-like bandwidths)
  bool group = false;    // with parzen.multivariate: per group of co-occurring parameters
  bool constant_liar = false;
};

// INVALID_ARGUMENT naming the option for startup_trials < 0, ei_candidates < 1, or group without
// multivariate.
absl::Status ValidateTpeOptions(const TpeOptions& options);

std::unique_ptr<Sampler> MakeTpeSampler(uint64_t seed, Direction direction,
                                        const TpeOptions& options);

// The size of the "below" set for n finished trials: min(ceil(n / 10), 25).
int Gamma(int n);

// The below/above split of `history`: the best `below` complete trials, then pruned trials by
// (deepest step, last value) while places remain; running trials above. Both in trial order.
struct Split {
  std::vector<const StudyTrial*> below;
  std::vector<const StudyTrial*> above;
};
Split SplitTrials(const std::vector<const StudyTrial*>& history, int below, Direction direction);

// The groups of parameters that always occur together in `finished` trials, each in the
// space's order, the groups ordered by their first parameter.
std::vector<std::vector<std::string>> GroupParameters(
    const run::SearchSpace& space, const std::vector<const StudyTrial*>& finished);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_TPE_SAMPLER_H_
