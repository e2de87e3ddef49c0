// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_DYNAMIC_CONTEXT_ENV_H_
#define DCS_ENV_DYNAMIC_CONTEXT_ENV_H_

// The dynamic-context wrapper (the paper's DynamicCARLEnv; docs/reference.md, "Step timing"): one
// environment slot whose context features start each episode from a pool and move within it
// along schedules, with the context shown to the policy in one of three modes.
//
// Reset, in order: draw each pooled feature's initial value (the slot's "pool" stream), apply
// the whole context (every reset, unconditionally, so nothing drifts into the next episode),
// reset the environment (the "reset" stream), reset each schedule (which may adjust the
// value), record the episode's initial context.
// Step: the first transition of an episode makes no schedule call; before every later
// transition each schedule is called with k = 1, 2, ... and its value written, so the update
// takes effect in the same physics step and the returned observation shows it.
//
// Observed context, as float32 in `observed_features` order, each normalised by its feature's
// sensor bounds (env/context_feature.h): kNone shows nothing (the paper's "blind"); kInitial
// the episode's initial values; kLive the current values (the paper's "observed"). A policy's
// input is [observation, context] in that order.
//
// Randomness: episode e of slot s draws from StreamSeed(run_seed, "pool", {s, e}) and
// StreamSeed(run_seed, "reset", {s, e}); schedules from their own seeds (env/schedule.h). So
// an episode is a function of (run seed, slot, episode) alone.
//
// `Env` is an environment class with the shape of env/cartpole.h. Confined to one thread.

#include <cstdint>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "env/context_feature.h"
#include "env/context_pool.h"
#include "env/observe_mode.h"
#include "env/staged_schedule.h"
#include "env/step_result.h"

namespace dcs::env {

struct FeaturePool {
  int feature = 0;  // index into Env::Features()
  ContextPool pool;
};

struct FeatureSchedule {
  int feature = 0;
  std::vector<ScheduleStage> stages;  // one stage for a single schedule
};

struct DynamicContextOptions {
  std::vector<double> context;  // every feature's value, by index; empty: the defaults
  std::vector<FeaturePool> pools;
  ContextPool::Selection selection = ContextPool::Selection::kRandom;
  std::vector<FeatureSchedule> schedules;
  ObserveMode observe = ObserveMode::kNone;
  std::vector<int> observed_features;  // empty with kNone, non-empty otherwise
  uint64_t run_seed = 0;
  uint64_t slot = 0;
};

template <typename Env>
class DynamicContextEnv {
 public:
  using Observation = typename Env::Observation;
  using ActionElement = typename Env::ActionElement;

  // INVALID_ARGUMENT, naming the problem, for: a context that is not valid for Env; a feature
  // index out of range or pooled/scheduled twice; a pool value or a schedule's bounds outside
  // the feature's physical bounds; an observe mode inconsistent with `observed_features`.
  static absl::StatusOr<DynamicContextEnv> Create(DynamicContextOptions options);

  // The number of context values shown to the policy.
  int context_size() const { return static_cast<int>(options_.observed_features.size()); }

  // Starts the next episode; `global_step` (environment steps of the run so far) selects the
  // stage of multi-stage schedules.
  void Reset(int64_t global_step, std::span<Observation, Env::kObservationSize> observation,
             std::span<float> context);

  StepResult Step(std::span<const ActionElement, Env::kActionSize> action,
                  std::span<Observation, Env::kObservationSize> observation,
                  std::span<float> context);

  // The slot's index in its run (DynamicContextOptions::slot): the key of its randomness.
  uint64_t slot_index() const { return options_.slot; }
  // Every feature's current value, by index.
  double feature(int index) const { return env_.GetFeature(index); }
  // The episode count of this slot (the first episode is 0).
  int64_t episode() const { return episode_; }
  // Transitions taken in the current episode.
  int64_t episode_steps() const { return steps_; }

  // Makes the next Reset start episode `episode` (a resumed run replays a slot's running
  // episode: the same episode number gives the same initial context, state and schedule).
  void SetNextEpisode(int64_t episode) { episode_ = episode - 1; }

  Env& env() { return env_; }

 private:
  struct Scheduled {
    int feature;
    StagedSchedule schedule;
  };

  DynamicContextEnv(DynamicContextOptions options, std::vector<Scheduled> scheduled)
      : options_(std::move(options)), scheduled_(std::move(scheduled)) {}

  void WriteContext(std::span<float> context) const;

  DynamicContextOptions options_;
  std::vector<Scheduled> scheduled_;
  Env env_;
  std::vector<double> initial_context_;  // the episode's values after reset, by feature
  int64_t episode_ = -1;
  int64_t steps_ = 0;
};

// Implementation details.

template <typename Env>
absl::StatusOr<DynamicContextEnv<Env>> DynamicContextEnv<Env>::Create(
    DynamicContextOptions options) {
  const ContextSpace& space = Env::Features();
  if (options.context.empty()) options.context = space.Defaults();
  if (static_cast<int>(options.context.size()) != space.size()) {
    return absl::InvalidArgumentError(absl::StrCat("a context needs ", space.size(),
                                                   " values, got ", options.context.size()));
  }
  DCS_RETURN_IF_ERROR(Env::ValidateContext(options.context));

  std::vector<bool> pooled(space.size(), false);
  std::vector<bool> scheduled(space.size(), false);
  auto check_feature = [&space](int feature, std::vector<bool>& seen,
                                absl::string_view what) -> absl::Status {
    if (feature < 0 || feature >= space.size()) {
      return absl::InvalidArgumentError(absl::StrCat(what, " names feature index ", feature,
                                                     ", which does not exist"));
    }
    if (seen[feature]) {
      return absl::InvalidArgumentError(
          absl::StrCat("feature '", space.feature(feature).name, "' has two ", what, "s"));
    }
    seen[feature] = true;
    return absl::OkStatus();
  };
  for (const FeaturePool& pool : options.pools) {
    DCS_RETURN_IF_ERROR(check_feature(pool.feature, pooled, "pool"));
    for (double value : pool.pool.values()) {
      DCS_RETURN_IF_ERROR(space.Validate(pool.feature, value));
    }
  }
  std::vector<Scheduled> schedules;
  for (FeatureSchedule& feature_schedule : options.schedules) {
    DCS_RETURN_IF_ERROR(check_feature(feature_schedule.feature, scheduled, "schedule"));
    for (const ScheduleStage& stage : feature_schedule.stages) {
      DCS_RETURN_IF_ERROR(space.Validate(feature_schedule.feature, stage.spec.min_value));
      DCS_RETURN_IF_ERROR(space.Validate(feature_schedule.feature, stage.spec.max_value));
    }
    DCS_ASSIGN_OR_RETURN(StagedSchedule staged, StagedSchedule::Create(feature_schedule.stages));
    schedules.push_back({feature_schedule.feature, std::move(staged)});
  }
  const bool blind = options.observe == ObserveMode::kNone;
  if (blind != options.observed_features.empty()) {
    return absl::InvalidArgumentError(
        blind ? "observe mode none shows no context, but observed features were given"
              : "observe modes live and initial need the features to observe");
  }
  std::vector<bool> observed(space.size(), false);
  for (int feature : options.observed_features) {
    DCS_RETURN_IF_ERROR(check_feature(feature, observed, "observation"));
  }
  return DynamicContextEnv(std::move(options), std::move(schedules));
}

template <typename Env>
void DynamicContextEnv<Env>::Reset(int64_t global_step,
                                   std::span<Observation, Env::kObservationSize> observation,
                                   std::span<float> context) {
  ++episode_;
  steps_ = 0;
  const uint64_t episode = static_cast<uint64_t>(episode_);
  initial_context_ = options_.context;
  Random pool_random(StreamSeed(options_.run_seed, "pool", {options_.slot, episode}));
  for (const FeaturePool& pool : options_.pools) {
    initial_context_[pool.feature] =
        pool.pool.Select(options_.selection, episode, options_.slot, pool_random);
  }
  for (size_t i = 0; i < initial_context_.size(); ++i) {
    env_.SetFeature(static_cast<int>(i), initial_context_[i]);
  }
  Random reset_random(StreamSeed(options_.run_seed, "reset", {options_.slot, episode}));
  env_.Reset(reset_random, observation);
  for (Scheduled& s : scheduled_) {
    const double value = s.schedule.Reset(initial_context_[s.feature],
                                          {.episode = episode, .slot = options_.slot},
                                          global_step);
    env_.SetFeature(s.feature, value);
    initial_context_[s.feature] = value;
  }
  WriteContext(context);
}

template <typename Env>
StepResult DynamicContextEnv<Env>::Step(
    std::span<const ActionElement, Env::kActionSize> action,
    std::span<Observation, Env::kObservationSize> observation, std::span<float> context) {
  if (steps_ > 0) {
    for (Scheduled& s : scheduled_) {
      env_.SetFeature(s.feature, s.schedule.Next(steps_, env_.GetFeature(s.feature)));
    }
  }
  const StepResult result = env_.Step(action, observation);
  ++steps_;
  WriteContext(context);
  return result;
}

template <typename Env>
void DynamicContextEnv<Env>::WriteContext(std::span<float> context) const {
  const ContextSpace& space = Env::Features();
  for (size_t i = 0; i < options_.observed_features.size(); ++i) {
    const int feature = options_.observed_features[i];
    const double value = options_.observe == ObserveMode::kLive ? env_.GetFeature(feature)
                                                                 : initial_context_[feature];
    context[i] = NormalizeContext(space.feature(feature), value);
  }
}

}  // namespace dcs::env

#endif  // DCS_ENV_DYNAMIC_CONTEXT_ENV_H_
