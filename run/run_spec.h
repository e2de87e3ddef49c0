// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_SPEC_H_
#define DCS_RUN_RUN_SPEC_H_

// One training run as a user specifies it (`dcs train run.yaml`; later one run of a
// sweep): the environment and its context, how the varied feature starts each episode and moves
// within it, what the policy observes, the evaluation protocol, PPO's settings, the budget and
// the seed. Features by name, not index: the run resolves them against the environment
// (run/run_plan.h). Plain data; thread-safe.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "actor/split.h"
#include "env/observe_mode.h"
#include "env/schedule_config.h"
#include "run/ppo_config.h"

namespace dcs::run {

// The coverage diagnostic (docs/reference.md, "Coverage"; run/coverage.h), off unless asked for:
// the cells of the environment's state projections that training visits, per window of `window`
// environment steps and over the run. Declared outside RunSpec (as RunSpec::Coverage): a class
// nested in RunSpec, with default member initialisers, would not be default-constructible inside
// RunSpec's own definition, and clang then refuses std::optional<Coverage>::emplace().
struct CoverageSpec {
  int64_t window = 50'000;
  std::vector<std::string> projections;  // by name; empty: every one the environment has
};

struct RunSpec {
  std::string env = "cartpole";
  uint64_t seed = 0;
  int64_t total_timesteps = 150'000;
  int n_envs = 1;

  // Values of context features other than their defaults, by name (e.g. PAYLOAD_MASS: 2.0).
  std::map<std::string, double> context;

  // The varied feature, its training range, and the pool the episode's initial value is drawn
  // from: `pool_values` if given, else pool-`pool_size` over the range (env/context_pool.h).
  std::string feature = "length";
  double range_lo = 0.35;
  double range_hi = 0.75;
  int pool_size = 1;
  std::vector<double> pool_values;

  // How the feature moves within an episode: one stage per entry; a single stage with
  // steps 0 runs for the whole run. No stages: static (identity).
  struct Stage {
    int64_t steps = 0;
    env::ScheduleConfig schedule;
  };
  std::vector<Stage> stages;

  // What the policy sees of the varied feature: nothing, its episode-initial value, or its live
  // value, normalised by its sensor bounds (env/dynamic_context_env.h).
  env::ObserveMode observe = env::ObserveMode::kNone;

  // Static evaluation (docs/reference.md, "Evaluation protocol"): every `eval_freq` environment
  // steps and at the end, `eval_episodes` deterministic episodes per context, on the varied
  // feature's values per split (indexed by actor::Split).
  int64_t eval_freq = 10'000;
  int eval_episodes = 30;
  std::array<std::vector<double>, actor::kNumSplits> eval_contexts;

  std::vector<double>& eval_values(actor::Split split) {
    return eval_contexts[static_cast<int>(split)];
  }
  const std::vector<double>& eval_values(actor::Split split) const {
    return eval_contexts[static_cast<int>(split)];
  }

  PpoConfig ppo;

  using Coverage = CoverageSpec;
  std::optional<Coverage> coverage;  // off unless asked for
};

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_SPEC_H_
