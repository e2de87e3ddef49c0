// Copyright 2026 The DCS Authors.
#include "run/run_plan.h"

#include <algorithm>
#include <limits>

#include "common/random.h"
#include "common/status_macros.h"
#include "env/context_pool.h"
#include "env/schedule_config.h"
#include "run/run_spec_yaml.h"

namespace dcs::run {

absl::StatusOr<RunPlan> PlanRun(const RunSpec& spec, const env::ContextSpace& space) {
  DCS_RETURN_IF_ERROR(ValidateRunSpec(spec));
  RunPlan plan;
  DCS_ASSIGN_OR_RETURN(plan.feature, space.IndexOf(spec.feature));
  env::DynamicContextOptions& slot = plan.slot;
  DCS_ASSIGN_OR_RETURN(slot.context, space.WithValues(spec.context));
  slot.context[plan.feature] = (spec.range_lo + spec.range_hi) / 2;

  DCS_ASSIGN_OR_RETURN(env::ContextPool pool,
                       spec.pool_values.empty()
                           ? env::ContextPool::OfSize(spec.range_lo, spec.range_hi, spec.pool_size)
                           : env::ContextPool::OfValues(spec.pool_values));
  slot.pools.push_back({.feature = plan.feature, .pool = std::move(pool)});
  slot.selection = env::ContextPool::Selection::kRoundRobin;

  if (!spec.stages.empty()) {
    env::FeatureSchedule schedule{.feature = plan.feature};
    int64_t start = 0;
    for (size_t k = 0; k < spec.stages.size(); ++k) {
      const RunSpec::Stage& stage = spec.stages[k];
      const uint32_t seed = StreamSeed(spec.seed, "schedule", {k}).GenerateState32(1)[0];
      DCS_ASSIGN_OR_RETURN(
          env::ScheduleSpec parsed,
          env::ParseScheduleSpec(stage.schedule, spec.range_lo, spec.range_hi, seed));
      // A single stage of steps 0 runs for the whole run.
      const int64_t steps = stage.steps > 0 ? stage.steps : std::numeric_limits<int64_t>::max();
      schedule.stages.push_back({.steps = steps, .spec = std::move(parsed)});
      if (k + 1 < spec.stages.size()) plan.stage_boundaries.push_back(start += stage.steps);
    }
    slot.schedules.push_back(std::move(schedule));
  }

  slot.observe = spec.observe;
  if (slot.observe != env::ObserveMode::kNone) slot.observed_features = {plan.feature};
  slot.run_seed = spec.seed;

  for (const auto& [split, name] : actor::kSplitNames) {
    for (double value : spec.eval_values(split)) plan.evaluation_contexts.push_back({split, value});
  }
  return plan;
}

std::vector<int64_t> EvaluationSteps(const RunSpec& spec, const RunPlan& plan) {
  std::vector<int64_t> steps;
  for (int64_t step = spec.eval_freq; step <= spec.total_timesteps; step += spec.eval_freq) {
    steps.push_back(step);
  }
  for (int64_t boundary : plan.stage_boundaries) {
    if (boundary < spec.total_timesteps) steps.push_back(boundary);
  }
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

}  // namespace dcs::run
