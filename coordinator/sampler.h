// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SAMPLER_H_
#define DCS_COORDINATOR_SAMPLER_H_

// A study's samplers (Optuna 4.9's TPESampler and RandomSampler): given the search space and the
// study's trials so far, the values of a new trial's parameters. Samplers keep no state between
// trials: a trial's values are a function of the sampler's seed, the trial's number and the other
// trials, drawn from the named stream StreamSeed(seed, "trial", {number}) (docs/architecture.md
// §6). So a study whose coordinator restarts resumes its sampler exactly, and trials may be asked
// in any order. Thread-safe (const).

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "common/enum_names.h"
#include "common/random.h"
#include "run/search_space.h"

namespace dcs::coordinator {

enum class TrialState { kRunning, kComplete, kPruned, kFailed };
inline constexpr EnumName<TrialState> kTrialStateNames[] = {{TrialState::kRunning, "running"},
                                                            {TrialState::kComplete, "complete"},
                                                            {TrialState::kPruned, "pruned"},
                                                            {TrialState::kFailed, "failed"}};
static_assert(InEnumOrder(kTrialStateNames));

enum class Direction { kMinimize, kMaximize };
inline constexpr EnumName<Direction> kDirectionNames[] = {{Direction::kMinimize, "minimize"},
                                                          {Direction::kMaximize, "maximize"}};
static_assert(InEnumOrder(kDirectionNames));

// Whether objective value `a` is better than `b` in `direction` (strictly: equal is not better).
inline bool IsBetter(Direction direction, double a, double b) {
  return direction == Direction::kMinimize ? a < b : a > b;
}

// A trial as a sampler sees it.
struct StudyTrial {
  int64_t number = 0;
  TrialState state = TrialState::kRunning;
  double value = 0;                    // the objective, for a complete trial (may be ±inf)
  run::ParameterValues values;         // its parameters so far
  std::map<int64_t, double> reported;  // step -> intermediate value (ranks pruned trials)
};

class Sampler {
 public:
  virtual ~Sampler() = default;
  // The values of trial `number`'s active parameters, in the space's order, given the study's other
  // `trials` (any order; the current trial, if among them, is ignored). REQUIRES: `space` is valid
  // (run::ValidateSearchSpace).
  virtual run::ParameterValues Sample(const run::SearchSpace& space,
                                      const std::vector<StudyTrial>& trials,
                                      int64_t number) const = 0;
};

// Uniform sampling (Optuna's RandomSampler): each active parameter uniform over its working space
// (log ranges log-uniform, grids and integers uniform over their cells), a categorical uniform over
// its choices.
std::unique_ptr<Sampler> MakeRandomSampler(uint64_t seed);

// One parameter drawn as the random sampler draws it.
double RandomValue(const run::Distribution& distribution, Random& random);
// A trial's active parameters, in the space's order, drawn as the random sampler draws them.
run::ParameterValues RandomValues(const run::SearchSpace& space, Random& random);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SAMPLER_H_
