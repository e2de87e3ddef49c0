// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_TRAINING_RUN_H_
#define DCS_LEARNER_TRAINING_RUN_H_

// One training run in one process (`dcs train`): a TrainingSession (learner/training_session.h)
// driven by a rollout collector over the run's own environment slots, evaluations run here as
// they fall due, and checkpoints and the evaluation log written to the run's directory. The run
// collects n_steps per slot, learns from it, and repeats until total_timesteps have been
// collected (the last rollout is whole, so a run may pass the budget by less than one rollout,
// as SB3's does).
//
// Checkpoints (run/run_checkpoint.h) are written when the session says one is due (after an
// update that followed an evaluation, and at the end) and when `on_update` asks to stop; the
// evaluation log (run/evaluation_log.h) with each. A resumed run continues from the latest
// checkpoint exactly: the slots' running episodes are replayed from their journals, so stopping
// and resuming ends with the same weights, bit for bit, as running straight through.
//
// Confined to one thread.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "actor/rollout_collector.h"
#include "common/status_macros.h"
#include "dcs/v1/evaluation.pb.h"
#include "env/vector_env.h"
#include "learner/training_session.h"
#include "run/evaluation_log.h"
#include "run/phase_seconds.h"
#include "run/run_checkpoint.h"
#include "run/run_spec.h"

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
  double recent_episode_length = 0;  // their mean length (SB3's ep_len_mean); NaN before one
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
  run::RunState state;
  bool complete = false;  // false if on_update stopped the run
  v1::EvaluationLog log;
  std::vector<float> parameters;  // PpoLearner::Parameters at the end
  run::PhaseSeconds seconds;      // this process's part (a resumed run's since it resumed)
};

// Trains `spec` on `Env`. INVALID_ARGUMENT for a spec the environment cannot carry out
// (naming the field); for a non-finite observation or reward (naming the rollout, step and
// slot: nothing is learnt from it); FAILED_PRECONDITION when resuming from a checkpoint of a
// different run (seed or shapes), NOT_FOUND when there is none; errors writing checkpoints or
// the log name the file. Whatever fails, the checkpoints already written stay valid.
template <typename Env>
absl::StatusOr<TrainingResult> Train(const run::RunSpec& spec, const TrainingOptions& options);

// Implementation details.

template <typename Env>
absl::StatusOr<TrainingResult> Train(const run::RunSpec& spec, const TrainingOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<run::Checkpoint> checkpoint;
  if (options.resume) {
    DCS_ASSIGN_OR_RETURN(checkpoint, run::ReadLatestCheckpoint(options.out_dir));
  }
  DCS_ASSIGN_OR_RETURN(
      const std::unique_ptr<TrainingSession> session,
      TrainingSession::Create<Env>(spec, checkpoint.has_value() ? &*checkpoint : nullptr));
  const run::RunPlan& plan = session->plan();

  std::vector<env::DynamicContextOptions> slots(spec.n_envs, plan.slot);
  for (int i = 0; i < spec.n_envs; ++i) slots[i].slot = static_cast<uint64_t>(i);
  DCS_ASSIGN_OR_RETURN(env::VectorEnv<Env> envs, env::VectorEnv<Env>::Create(std::move(slots)));
  const int64_t first_timesteps = session->state().timesteps;
  envs.set_global_steps(first_timesteps);
  actor::RolloutCollector<Env> collector(envs, spec.seed, session->state().journals);
  // Acts as actors do (actor/policy_network.h), refreshed after every update.
  DCS_ASSIGN_OR_RETURN(actor::PolicyNetwork policy,
                       actor::PolicyNetwork::Create(session->ActorWeights()));

  run::PhaseSeconds seconds;
  // Runs `phase` and returns what it returns, adding its wall time to `total`.
  const auto timed = [](double& total, auto&& phase) {
    struct Stopwatch {
      double& total;
      const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
      ~Stopwatch() {
        total += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
    } stopwatch{total};
    return phase();
  };

  auto evaluate = [&](const EvaluationDue& due) -> absl::Status {
    DCS_ASSIGN_OR_RETURN(const actor::EvaluationResult evaluation,
                         timed(seconds.evaluations, [&] {
                           return actor::Evaluate<Env>(policy, plan.slot, plan.feature,
                                                       plan.evaluation_contexts,
                                                       spec.eval_episodes, spec.seed);
                         }));
    session->RecordEvaluation(due, evaluation);
    return absl::OkStatus();
  };
  auto save = [&]() -> absl::Status {
    if (options.out_dir.empty()) return absl::OkStatus();
    return timed(seconds.checkpoints, [&]() -> absl::Status {
      DCS_ASSIGN_OR_RETURN(const run::Checkpoint latest, session->Checkpoint());
      DCS_RETURN_IF_ERROR(run::WriteCheckpoint(options.out_dir, latest.state, latest.learner,
                                               options.keep_checkpoints));
      return run::WriteEvaluationLog(options.out_dir, session->EvaluationLog());
    });
  };

  while (!session->complete()) {
    actor::Rollout rollout;
    std::vector<actor::EpisodeSummary> finished;
    timed(seconds.rollouts, [&] {
      collector.Collect(policy, spec.ppo.n_steps, session->state().rollouts, rollout, finished);
    });
    DCS_ASSIGN_OR_RETURN(const std::optional<EvaluationDue> due,
                         session->AddRollout(std::move(rollout), finished, collector.journals()));
    if (due.has_value()) DCS_RETURN_IF_ERROR(evaluate(*due));
    DCS_ASSIGN_OR_RETURN(const SessionUpdate update,
                         timed(seconds.updates, [&] { return session->Update(); }));
    DCS_ASSIGN_OR_RETURN(policy, actor::PolicyNetwork::Create(session->ActorWeights()));
    if (update.final_evaluation.has_value()) {
      DCS_RETURN_IF_ERROR(evaluate(*update.final_evaluation));
    }

    bool keep_going = true;
    if (options.on_update) {
      const run::RunState& state = session->state();
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      keep_going = options.on_update(
          {.timesteps = state.timesteps,
           .total_timesteps = spec.total_timesteps,
           .updates = session->policy_version(),
           .steps_per_second = static_cast<double>(state.timesteps - first_timesteps) / elapsed,
           .recent_return = session->recent_return(),
           .recent_episode_length = session->recent_episode_length(),
           .update = update.stats,
           .evaluation = state.evaluations.empty() ? nullptr : &state.evaluations.back()});
    }
    if (session->checkpoint_due() || !keep_going) DCS_RETURN_IF_ERROR(save());
    if (!keep_going) break;
  }
  return TrainingResult{.state = session->state(),
                        .complete = session->complete(),
                        .log = session->EvaluationLog(),
                        .parameters = session->Parameters(),
                        .seconds = seconds};
}

}  // namespace dcs::learner

#endif  // DCS_LEARNER_TRAINING_RUN_H_
