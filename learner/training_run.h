// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TRAINING_RUN_H_
#define DCS_LEARNER_TRAINING_RUN_H_

// One training run in one process, as Stable-Baselines3's PPO.learn with the paper's evaluation
// callback (`dcs train`): collect a rollout of n_steps per slot, learn from it, repeat until
// total_timesteps have been collected (the last rollout is whole, so a run may pass the budget
// by less than one rollout, as SB3's does).
//
// Evaluation (spec/schedules.md §9): at every step of EvaluationSteps (learner/run_plan.h) and
// at the end. SB3 evaluates in the middle of the rollout during which the step count reaches an
// evaluation step, with the policy that is collecting it; a run here evaluates that same policy
// right after the rollout, before learning from it, and records the evaluation at that step.
// The results are therefore those of SB3's schedule, without interleaving evaluation episodes
// with the training environments' steps.
//
// Checkpoints (learner/run_checkpoint.h) are written after every update that followed an
// evaluation, at the end, and when `on_update` asks to stop; the evaluation log
// (learner/evaluation_log.h) after every evaluation. A resumed run continues from the latest
// checkpoint exactly: every random stream derives from the seed and counters (the slots'
// running episodes are replayed from their journals), so stopping and resuming ends with the
// same weights, bit for bit, as running straight through. The same spec and seed give the same
// result bit for bit (with libtorch on one thread: learner/torch_runtime.h).
//
// Confined to one thread.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "actor/evaluation.h"
#include "actor/mlp_policy.h"
#include "actor/rollout_collector.h"
#include "common/status_macros.h"
#include "env/vector_env.h"
#include "learner/evaluation_log.h"
#include "learner/ppo_learner.h"
#include "learner/run_checkpoint.h"
#include "learner/run_plan.h"
#include "learner/run_spec.h"

namespace dcs::learner {

// What a run reports after each update.
struct TrainingProgress {
  int64_t timesteps = 0;
  int64_t total_timesteps = 0;
  int64_t updates = 0;
  double steps_per_second = 0;  // environment steps per wall second in this process
  // The mean return of the last 100 finished training episodes (SB3's ep_rew_mean); NaN
  // before the first.
  double recent_return = 0;
  UpdateStats update;
  const actor::EvaluationResult* evaluation = nullptr;  // the latest, if any
};

struct TrainingOptions {
  // Where checkpoints and the evaluation log go; empty: nowhere (nothing can be resumed).
  std::string out_dir;
  bool resume = false;  // continue from out_dir's latest checkpoint
  int keep_checkpoints = 3;
  // Called after every update; returning false stops the run after writing a checkpoint.
  std::function<bool(const TrainingProgress&)> on_update;
};

struct TrainingResult {
  RunState state;
  bool complete = false;  // false if on_update stopped the run
  v1::EvaluationLog log;
  std::vector<float> parameters;  // PpoLearner::Parameters at the end
};

// Trains `spec` on `Env`. INVALID_ARGUMENT for a spec the environment cannot carry out
// (naming the field); for a non-finite observation or reward (naming the rollout, step and
// slot: nothing is learnt from it); FAILED_PRECONDITION when resuming from a checkpoint of a
// different run (seed or shapes), NOT_FOUND when there is none; errors writing checkpoints or
// the log name the file. Whatever fails, the checkpoints already written stay valid.
template <typename Env>
absl::StatusOr<TrainingResult> Train(const RunSpec& spec, const TrainingOptions& options);

// Implementation details.

namespace training_internal {

constexpr size_t kRecentEpisodes = 100;  // SB3's ep_info_buffer

inline double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

}  // namespace training_internal

template <typename Env>
absl::StatusOr<TrainingResult> Train(const RunSpec& spec, const TrainingOptions& options) {
  constexpr bool kImage = std::is_same_v<typename Env::Observation, uint8_t>;
  const auto start = std::chrono::steady_clock::now();
  DCS_ASSIGN_OR_RETURN(const RunPlan plan, PlanRun(spec, Env::Features()));
  const std::vector<int64_t> evaluation_steps = EvaluationSteps(spec, plan);

  std::vector<env::DynamicContextOptions> slots(spec.n_envs, plan.slot);
  for (int i = 0; i < spec.n_envs; ++i) slots[i].slot = static_cast<uint64_t>(i);
  DCS_ASSIGN_OR_RETURN(env::VectorEnv<Env> envs, env::VectorEnv<Env>::Create(std::move(slots)));
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<PpoLearner> learner,
                       PpoLearner::Create(PolicySpecFor<Env>(envs.context_size()), spec.ppo,
                                          spec.n_envs, spec.seed));

  TrainingResult result;
  RunState& state = result.state;
  if (options.resume) {
    DCS_ASSIGN_OR_RETURN(Checkpoint checkpoint, ReadLatestCheckpoint(options.out_dir));
    DCS_RETURN_IF_ERROR(learner->LoadState(checkpoint.learner));
    state = std::move(checkpoint.state);
    if (static_cast<int>(state.journals.size()) != spec.n_envs) {
      return absl::FailedPreconditionError(
          absl::StrCat("checkpoint ", checkpoint.name, " of ", options.out_dir, " has ",
                       state.journals.size(), " environment slots, the run has n_envs ",
                       spec.n_envs));
    }
    envs.set_global_steps(state.timesteps);
  }
  actor::RolloutCollector<Env> collector(envs, spec.seed, state.journals);

  // The policy that acts: an Eigen copy of the actor network for vector observations (refreshed
  // after every update), libtorch's own network for images.
  std::optional<actor::MlpPolicy> mlp;
  auto refresh_policy = [&]() -> absl::Status {
    if constexpr (!kImage) {
      DCS_ASSIGN_OR_RETURN(mlp, actor::MlpPolicy::Create(learner->ActorWeights()));
    }
    return absl::OkStatus();
  };
  DCS_RETURN_IF_ERROR(refresh_policy());
  auto policy = [&]() -> actor::Policy& {
    if constexpr (kImage) {
      return *learner;
    } else {
      return *mlp;
    }
  };

  auto evaluate = [&](int64_t step) -> absl::Status {
    DCS_ASSIGN_OR_RETURN(actor::EvaluationResult evaluation,
                         actor::Evaluate<Env>(policy(), plan.slot, plan.feature,
                                              plan.evaluation_contexts, spec.eval_episodes,
                                              spec.seed));
    evaluation.step = step;
    evaluation.updates = learner->updates();
    state.evaluations.push_back(std::move(evaluation));
    return absl::OkStatus();
  };
  auto save = [&](bool complete) -> absl::Status {
    if (options.out_dir.empty()) return absl::OkStatus();
    state.journals = collector.journals();
    DCS_ASSIGN_OR_RETURN(const std::string bytes, learner->SaveState());
    DCS_RETURN_IF_ERROR(WriteCheckpoint(options.out_dir, state, bytes, options.keep_checkpoints));
    return WriteEvaluationLog(
        options.out_dir,
        MakeEvaluationLog(spec, state.evaluations, plan.stage_boundaries, complete));
  };

  const int64_t rollout_steps = static_cast<int64_t>(spec.ppo.n_steps) * spec.n_envs;
  const int64_t first_timesteps = state.timesteps;
  actor::Rollout rollout;
  std::vector<actor::EpisodeSummary> finished;
  while (state.timesteps < spec.total_timesteps) {
    finished.clear();
    collector.Collect(policy(), spec.ppo.n_steps, state.rollouts, rollout, finished);
    for (const actor::EpisodeSummary& episode : finished) {
      state.recent_returns.push_back(episode.episode_return);
    }
    if (state.recent_returns.size() > training_internal::kRecentEpisodes) {
      state.recent_returns.erase(
          state.recent_returns.begin(),
          state.recent_returns.end() - training_internal::kRecentEpisodes);
    }
    const int64_t before = state.timesteps;
    state.timesteps += rollout_steps;

    // Every evaluation step this rollout reached, with the policy that collected it (they all
    // evaluate the same weights on the same episodes: one evaluation serves them all).
    bool evaluated = false;
    for (int64_t step : evaluation_steps) {
      if (step <= before || step > state.timesteps) continue;
      if (evaluated) {
        actor::EvaluationResult copy = state.evaluations.back();
        copy.step = step;
        state.evaluations.push_back(std::move(copy));
      } else {
        DCS_RETURN_IF_ERROR(evaluate(step));
        evaluated = true;
      }
    }

    absl::StatusOr<UpdateStats> stats = learner->Update(rollout);
    if (!stats.ok()) {
      return absl::Status(stats.status().code(),
                          absl::StrCat("environment steps ", before, " to ", state.timesteps,
                                       ": ", stats.status().message()));
    }
    ++state.rollouts;
    DCS_RETURN_IF_ERROR(refresh_policy());
    const bool complete = state.timesteps >= spec.total_timesteps;
    if (complete) DCS_RETURN_IF_ERROR(evaluate(state.timesteps));

    bool keep_going = true;
    if (options.on_update) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      keep_going = options.on_update(
          {.timesteps = state.timesteps,
           .total_timesteps = spec.total_timesteps,
           .updates = learner->updates(),
           .steps_per_second = static_cast<double>(state.timesteps - first_timesteps) / seconds,
           .recent_return = training_internal::Mean(state.recent_returns),
           .update = *stats,
           .evaluation = state.evaluations.empty() ? nullptr : &state.evaluations.back()});
    }
    if (evaluated || complete || !keep_going) DCS_RETURN_IF_ERROR(save(complete));
    if (!keep_going) break;
  }

  result.complete = state.timesteps >= spec.total_timesteps;
  state.journals = collector.journals();
  result.log = MakeEvaluationLog(spec, state.evaluations, plan.stage_boundaries, result.complete);
  result.parameters = learner->Parameters();
  return result;
}

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TRAINING_RUN_H_
