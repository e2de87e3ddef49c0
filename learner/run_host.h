// Copyright 2026 The DCS Authors.
#ifndef DCS_LEARNER_RUN_HOST_H_
#define DCS_LEARNER_RUN_HOST_H_

// One run hosted by a learner for remote actors: a TrainingSession (learner/training_session.h)
// fed one env slot at a time. The learner service adapts it to the wire; it knows nothing of
// gRPC and runs in one process in tests.
//
//   actors, on any thread            the run's own thread
//   ───────────────────────          ────────────────────
//   SlotWork(slot) ─▶ rollout r, policy version r, the slot's journal if it must rebuild
//   PushRollout(slot, r, data) ─▶    Step(): once every slot's rollout r is in, learns from
//                                    it (evaluating when one falls due) and publishes r + 1
//
// On-policy, as SB3 and `dcs train`: rollout r is collected with policy version r by every
// slot; a run hosted here ends with the same weights and evaluations, bit for bit, as
// `dcs train` in one process, whichever actors step its slots and however often they change
// (a slot is rebuilt from its journal: env/vector_env.h ReplaySlot).
//
// Evaluations are the Evaluator's: on threads of this process (EvaluateInProcess), or on
// actors through the coordinator (the learner service's). Each runs on a thread of its own with
// the policy that fell due while training goes on, and they are recorded in the order they
// fell due. A checkpoint that falls due is taken once no evaluation is outstanding (so it holds
// every evaluation up to its step), at the latest when the next one falls due (training then
// waits for the evaluations); the run is complete once its last evaluation is in.
//
// Slot leases: each slot's holder names the epoch its lease was granted at; the host serves
// the newest epoch it has seen per slot and refuses older ones (FAILED_PRECONDITION).
//
// Thread-safety: SlotWork and PushRollout from any thread; Step from one thread at a time.

#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "absl/time/time.h"
#include "actor/evaluation.h"
#include "actor/policy_network.h"
#include "actor/policy_weights.h"
#include "actor/rollout_collector.h"
#include "actor/slot_rollout.h"
#include "common/status_macros.h"
#include "dcs/v1/evaluation.pb.h"
#include "learner/training_run.h"
#include "learner/training_session.h"
#include "run/run_checkpoint.h"
#include "run/run_spec.h"

namespace dcs::learner {

// What a slot collects next.
struct SlotWork {
  bool ready = false;         // false: the rollout it delivered is not learnt from yet
  bool run_complete = false;  // nothing more to collect
  int64_t rollout = 0;        // collect this rollout with policy version `rollout`
  int64_t start_timesteps = 0;
  int n_steps = 0;
  std::shared_ptr<const actor::PolicyWeights> weights;  // policy version `rollout`
  absl::Time published_at;                              // when that version was published
  // Where the slot's episode stands before `rollout`: given when the holder is not
  // positioned there (it must rebuild the slot).
  std::optional<actor::SlotJournal> journal;
};

// One evaluation a host asks of its Evaluator: the policy `due` names, `weights`, on the run's
// evaluation contexts (plan.evaluation_contexts), spec.eval_episodes episodes each.
struct EvaluationTask {
  const run::RunSpec& spec;
  const run::RunPlan& plan;
  EvaluationDue due;
  std::shared_ptr<const actor::PolicyWeights> weights;
};

// Evaluates a task, called on a thread of its own; returns CANCELLED soon after `stop` is
// notified if it has not finished by then (the host is stopping).
using Evaluator = std::function<absl::StatusOr<actor::EvaluationResult>(
    const EvaluationTask& task, const absl::Notification& stop)>;

// Evaluates on the calling thread, as `dcs train` does (actor::Evaluate).
template <typename Env>
Evaluator EvaluateInProcess();

// What one Step did.
struct HostStep {
  TrainingProgress progress;  // `evaluation` points into the host; valid until the next Step
  int64_t steps = 0;          // environment steps learnt from
  int64_t episodes = 0;       // training episodes that finished in them
  bool complete = false;
  // When the session says one is due (after an evaluation, and at the end).
  std::optional<run::Checkpoint> checkpoint;
  v1::EvaluationLog evaluation_log;  // with the checkpoint
};

class RunHost {
 public:
  // A host for `spec` on `Env`, continuing from `checkpoint` if given, evaluating with
  // `evaluator`. Errors as TrainingSession::Create.
  template <typename Env>
  static absl::StatusOr<std::unique_ptr<RunHost>> Create(run::RunSpec spec,
                                                         const run::Checkpoint* checkpoint,
                                                         Evaluator evaluator);

  // Stops, and waits for the outstanding evaluations to return.
  ~RunHost();
  RunHost(const RunHost&) = delete;
  RunHost& operator=(const RunHost&) = delete;

  int n_envs() const { return n_envs_; }
  int n_steps() const { return shape_.num_steps; }

  // The work of `slot` for its holder at `epoch`, positioned to collect rollout
  // `positioned_at` (-1: not at all). Waits up to `wait` for the next rollout if the slot's
  // current one is in. INVALID_ARGUMENT for a slot out of range; FAILED_PRECONDITION for an
  // epoch older than one seen.
  absl::StatusOr<SlotWork> GetSlotWork(int slot, int64_t epoch, int64_t positioned_at,
                                       absl::Duration wait);

  // Takes `data`, slot `data.slot`'s part of rollout `rollout`, collected with policy version
  // `policy_version` by the holder at `epoch`. Returns true for a rollout taken already (a
  // retry). Everything is checked before anything is taken: INVALID_ARGUMENT for a wrong shape
  // or a non-finite value (naming the field and step); FAILED_PRECONDITION for an old epoch,
  // a policy version other than the rollout's, or a rollout not being collected.
  absl::StatusOr<bool> PushRollout(int64_t epoch, int64_t rollout, int64_t policy_version,
                                   actor::SlotRollout data);

  // Waits until every slot's part of the current rollout is in (or Stop), then learns from it
  // as Train<Env> does and publishes the next policy version. CANCELLED after Stop; errors of
  // the session otherwise (the host is then not to be stepped again).
  absl::StatusOr<HostStep> Step();

  // Wakes Step and every waiting GetSlotWork, and cancels outstanding evaluations; Step then
  // returns CANCELLED.
  void Stop();

  // Calls `changed` whenever what GetSlotWork answers may have changed (a policy published,
  // the host stopped), after the change and under no lock of the host: for callers that wait
  // for work without holding a thread in GetSlotWork. REQUIRES: called at most once, before the
  // host is shared with other threads.
  void OnChange(std::function<void()> changed) { changed_ = std::move(changed); }

  // Whether the run has all its steps: resumed from the checkpoint of its end (its learner
  // stopped after storing it, before it could finish the run), it has nothing left to step.
  // Call from Step's thread.
  bool complete() const { return session_->complete(); }

  // Every parameter of the current policy (runs are compared with it). Call from Step's thread.
  std::vector<float> Parameters() const { return session_->Parameters(); }

 private:
  RunHost(std::unique_ptr<TrainingSession> session, Evaluator evaluator,
          actor::SlotRolloutShape shape);

  // Publishes the session's current policy and journals, and frees the slots' parts of the
  // rollout learnt from. Called from Step's thread.
  void Publish();
  // Starts evaluating the current policy for `due`.
  void StartEvaluation(const EvaluationDue& due);
  // Records the evaluations that have finished, in order; with `wait`, all of them.
  absl::Status RecordEvaluations(bool wait);
  // OK if `epoch` is not older than the newest seen for `slot`, which it then becomes.
  absl::Status CheckEpoch(int slot, int64_t epoch) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);

  // Fixed at construction.
  const std::unique_ptr<TrainingSession> session_;  // Step's thread only
  const Evaluator evaluator_;
  const int n_envs_;
  const actor::SlotRolloutShape shape_;  // of each slot's part
  const absl::Time start_;
  const int64_t first_timesteps_;
  std::function<void()> changed_;  // set before the host is shared; may be empty

  absl::Notification stop_;  // outlives evaluations_, whose threads watch it

  // Step's thread only.
  struct PendingEvaluation {
    EvaluationDue due;
    std::future<absl::StatusOr<actor::EvaluationResult>> result;
  };
  std::deque<PendingEvaluation> evaluations_;  // in the order they fell due
  bool checkpoint_wanted_ = false;

  absl::Mutex mu_;
  bool complete_ ABSL_GUARDED_BY(mu_) = false;
  int64_t rollout_ ABSL_GUARDED_BY(mu_) = 0;  // being collected
  int64_t start_timesteps_ ABSL_GUARDED_BY(mu_) = 0;
  std::shared_ptr<const actor::PolicyWeights> weights_ ABSL_GUARDED_BY(mu_);
  absl::Time published_at_ ABSL_GUARDED_BY(mu_);
  std::vector<actor::SlotJournal> journals_ ABSL_GUARDED_BY(mu_);  // before rollout_
  std::vector<int64_t> epochs_ ABSL_GUARDED_BY(mu_);
  std::vector<std::optional<actor::SlotRollout>> pending_ ABSL_GUARDED_BY(mu_);
  int pending_count_ ABSL_GUARDED_BY(mu_) = 0;
};

// Implementation details.

template <typename Env>
Evaluator EvaluateInProcess() {
  return [](const EvaluationTask& task,
            const absl::Notification& /*stop*/) -> absl::StatusOr<actor::EvaluationResult> {
    DCS_ASSIGN_OR_RETURN(actor::PolicyNetwork policy, actor::PolicyNetwork::Create(*task.weights));
    return actor::Evaluate<Env>(policy, task.plan.slot, task.plan.feature,
                                task.plan.evaluation_contexts, task.spec.eval_episodes,
                                task.spec.seed);
  };
}

template <typename Env>
absl::StatusOr<std::unique_ptr<RunHost>> RunHost::Create(run::RunSpec spec,
                                                         const run::Checkpoint* checkpoint,
                                                         Evaluator evaluator) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<TrainingSession> session,
                       TrainingSession::Create<Env>(std::move(spec), checkpoint));
  const run::PolicySpec policy =
      run::PolicySpecFor<Env>(static_cast<int>(session->plan().slot.observed_features.size()));
  const actor::SlotRolloutShape shape{
      .num_steps = session->spec().ppo.n_steps,
      .input = static_cast<size_t>(policy.flat_input_size()),
      .image = policy.image_size(),
      .action = static_cast<size_t>(policy.action_size)};
  std::unique_ptr<RunHost> host(new RunHost(std::move(session), std::move(evaluator), shape));
  host->Publish();
  return host;
}

}  // namespace dcs::learner

#endif  // DCS_LEARNER_RUN_HOST_H_
