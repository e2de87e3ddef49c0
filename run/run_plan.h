// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_PLAN_H_
#define DCS_RUN_RUN_PLAN_H_

// A validated RunSpec resolved against its environment: feature names become indices, the pool
// and the stages become the training slots' options, the evaluation grid a list of contexts,
// and the budget the steps at which the run evaluates. Training (learner/training_session.h) works
// from the plan only. Thread-safe (pure functions and plain data).

#include <cstdint>
#include <iterator>
#include <type_traits>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "env/context_feature.h"
#include "env/dynamic_context_env.h"
#include "run/ppo_config.h"
#include "run/run_spec.h"

namespace dcs::run {

struct RunPlan {
  int feature = 0;  // the varied feature's index
  // Training slot 0's options (slot i differs in `slot` only): the context, the pool with the
  // reference's round-robin selection (docs/reference.md, "Pools"), the stages, the observation
  // mode.
  env::DynamicContextOptions slot;
  std::vector<actor::EvaluationContext> evaluation_contexts;
  // The global steps where a stage ends and the next begins (empty for a single stage).
  std::vector<int64_t> stage_boundaries;
};

// Validates `spec` (run/run_spec_yaml.h: ValidateRunSpec) and resolves it against `space`.
// Stage k's schedule is seeded from StreamSeed(spec.seed, "schedule", {k}). INVALID_ARGUMENT
// as ValidateRunSpec.
absl::StatusOr<RunPlan> PlanRun(const RunSpec& spec, const env::ContextSpace& space);

// The steps at which the run evaluates, ascending: every multiple of `eval_freq` and every stage
// boundary below `total_timesteps` (docs/reference.md, "Multi-stage schedules"). The run also
// evaluates at its end, whatever step that falls on.
std::vector<int64_t> EvaluationSteps(const RunSpec& spec, const RunPlan& plan);

// The policy's shapes for `Env` with `context_size` observed context values.
template <typename Env>
PolicySpec PolicySpecFor(int context_size) {
  PolicySpec spec{.context_size = context_size, .action_size = Env::kActionSize};
  if constexpr (std::is_same_v<typename Env::Observation, uint8_t>) {
    spec.image_height = Env::kImageHeight;
    spec.image_width = Env::kImageWidth;
    spec.image_channels = Env::kImageChannels;
  } else {
    spec.observation_size = Env::kObservationSize;
  }
  if constexpr (std::is_integral_v<typename Env::ActionElement>) {
    spec.num_actions = Env::kNumActions;
  } else {
    spec.action_low.assign(std::begin(Env::kActionLow), std::end(Env::kActionLow));
    spec.action_high.assign(std::begin(Env::kActionHigh), std::end(Env::kActionHigh));
  }
  return spec;
}

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_PLAN_H_
