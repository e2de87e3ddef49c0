// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TRAINING_SESSION_H_
#define DCS_LEARNER_TRAINING_SESSION_H_

// One run's learning, a step at a time, as Stable-Baselines3's PPO.learn does it with the
// paper's evaluation callback: the learner service will host many of these; `dcs train` drives
// one in its own process (learner/training_run.h). Whoever steps the environments collects
// each rollout with the session's current policy; per rollout:
//
//   policy version v ─▶ the slots collect rollout r with v (in process, or on actors)
//   AddRollout(r) ──▶ an evaluation of v falls due if r reached an evaluation step
//   Update() ───────▶ policy version v + 1; after the last rollout, the final evaluation
//                     of v + 1 falls due
//   RecordEvaluation(due, result) for each evaluation due, whenever its result arrives
//   checkpoint_due() ▶ Checkpoint(): what to store (a run directory; later the coordinator)
//
// Evaluation steps are those of run::EvaluationSteps (every eval_freq and the stage
// boundaries); SB3 evaluates in the middle of the rollout that reaches one, with the policy
// collecting it, so an evaluation falls due with the policy that collected the rollout, before
// the update that learns from it. Several steps reached by one rollout share one evaluation.
//
// Deterministic: the same spec, seed and rollouts give the same weights and evaluations bit for
// bit (with libtorch on one thread: learner/torch_runtime.h), and a session created from a
// checkpoint continues exactly as the one that wrote it would have. After an error the session
// is not to be used further; its last checkpoint stays valid. Confined to one thread.

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "actor/policy_weights.h"
#include "actor/rollout.h"
#include "actor/rollout_collector.h"
#include "common/status_macros.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/state_projection.h"
#include "learner/ppo_learner.h"
#include "run/coverage.h"
#include "run/run_checkpoint.h"
#include "run/run_plan.h"
#include "run/run_spec.h"

namespace dcs::learner {

// An evaluation a session is owed: of the policy that was current when it fell due, to be
// recorded at each of `steps` (environment steps of training).
struct EvaluationDue {
  std::vector<int64_t> steps;
  int64_t policy_version = 0;
};

struct SessionUpdate {
  UpdateStats stats;
  // Once the run is complete: the evaluation of the final policy, at the last step.
  std::optional<EvaluationDue> final_evaluation;
};

class TrainingSession {
 public:
  // A session training `spec` on `Env`: the plan (run::PlanRun), the learner with its initial
  // weights from the seed. With `checkpoint`, it continues from there. INVALID_ARGUMENT as
  // PlanRun or for coverage the environment cannot count; FAILED_PRECONDITION for a checkpoint of
  // another run (seed, network shapes, number of slots or coverage projections); DATA_LOSS for
  // one whose learner state does not load.
  template <typename Env>
  static absl::StatusOr<std::unique_ptr<TrainingSession>> Create(
      run::RunSpec spec, const run::Checkpoint* checkpoint = nullptr);

  TrainingSession(const TrainingSession&) = delete;
  TrainingSession& operator=(const TrainingSession&) = delete;

  const run::RunSpec& spec() const { return spec_; }
  const run::RunPlan& plan() const { return plan_; }
  // Counters, the slots' journals (one per slot; in a new run each at the reset of episode 0),
  // the last training episodes' returns, the evaluations, the coverage counted if the spec asks
  // for it (run/coverage.h: the session counts every rollout it is given).
  const run::RunState& state() const { return state_; }
  bool complete() const { return state_.timesteps >= spec_.total_timesteps; }

  // The current policy: its version (the updates so far) and its actor network, for Eigen
  // inference (actor/policy_network.h).
  int64_t policy_version() const { return learner_->updates(); }
  actor::PolicyWeights ActorWeights() const { return learner_->ActorWeights(); }

  // Takes rollout number state().rollouts, collected by every slot with the current policy,
  // with the training episodes that finished in it and every slot's journal after it. Returns
  // the evaluation of the current policy that fell due, if the rollout reached an evaluation
  // step. FAILED_PRECONDITION if the run is complete or a rollout waits for its update;
  // INVALID_ARGUMENT if the rollout is not n_steps of every slot, or the journals are not one
  // per slot.
  absl::StatusOr<std::optional<EvaluationDue>> AddRollout(
      actor::Rollout rollout, std::span<const actor::EpisodeSummary> finished,
      std::vector<actor::SlotJournal> journals);

  // Learns from the waiting rollout; the policy version goes up by one. FAILED_PRECONDITION
  // without one; otherwise errors as PpoLearner::Update, naming the rollout's environment steps
  // (the weights are then untouched).
  absl::StatusOr<SessionUpdate> Update();

  // Records `result`, the evaluation of the policy `due` names, at each of its steps.
  void RecordEvaluation(const EvaluationDue& due, const actor::EvaluationResult& result);

  // True from an update that learnt from a rollout that reached an evaluation step, or that
  // completed the run, until the next rollout: a checkpoint then holds a new evaluation.
  bool checkpoint_due() const { return checkpoint_due_; }

  // The state to continue from, named after its step. INTERNAL if the learner cannot
  // serialise itself.
  absl::StatusOr<run::Checkpoint> Checkpoint() const;

  // The evaluation log so far (run/evaluation_log.h), with the coverage so far.
  v1::EvaluationLog EvaluationLog() const;

  // The mean return of the last 100 finished training episodes (SB3's ep_rew_mean); NaN before
  // the first.
  double recent_return() const;
  // Their mean length in environment steps (SB3's ep_len_mean); NaN before the first.
  double recent_episode_length() const;

  // Every parameter, flattened in a fixed order (runs are compared with it).
  std::vector<float> Parameters() const { return learner_->Parameters(); }

 private:
  TrainingSession(run::RunSpec spec, run::RunPlan plan,
                  std::vector<env::StateProjection> coverage_projections,
                  std::unique_ptr<PpoLearner> learner);

  // `projections`: the environment's (run::EnvironmentProjections).
  static absl::StatusOr<std::unique_ptr<TrainingSession>> Create(
      run::RunSpec spec, run::RunPlan plan, const run::PolicySpec& policy,
      const std::vector<env::StateProjection>& projections, const run::Checkpoint* checkpoint);

  // Fixed at construction.
  const run::RunSpec spec_;
  const run::RunPlan plan_;
  const std::vector<int64_t> evaluation_steps_;
  const std::vector<env::StateProjection> coverage_projections_;  // empty: coverage is off
  const std::unique_ptr<PpoLearner> learner_;

  run::RunState state_;
  std::optional<actor::Rollout> waiting_;  // added, not yet learnt from
  int64_t waiting_from_ = 0;               // the environment step the waiting rollout began at
  bool waiting_reached_evaluation_ = false;
  bool checkpoint_due_ = false;
};

// Implementation details.

template <typename Env>
absl::StatusOr<std::unique_ptr<TrainingSession>> TrainingSession::Create(
    run::RunSpec spec, const run::Checkpoint* checkpoint) {
  DCS_ASSIGN_OR_RETURN(run::RunPlan plan, run::PlanRun(spec, Env::Features()));
  const run::PolicySpec policy =
      run::PolicySpecFor<Env>(static_cast<int>(plan.slot.observed_features.size()));
  return Create(std::move(spec), std::move(plan), policy, run::EnvironmentProjections<Env>(),
                checkpoint);
}

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TRAINING_SESSION_H_
