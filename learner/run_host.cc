// Copyright 2026 The DCS Authors.
#include "learner/run_host.h"

#include <chrono>
#include <cmath>
#include <span>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"

namespace dcs::learner {
namespace {

// OK if every value is finite; otherwise names the field and the row of the first that is not.
absl::Status CheckFinite(absl::string_view field, std::span<const float> values, int row_size) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return absl::InvalidArgumentError(absl::StrCat(field, " at step ", i / row_size, " is ",
                                                     values[i], "; values must be finite"));
    }
  }
  return absl::OkStatus();
}

// The whole of one slot's part checked against the run's shapes, before anything is taken.
absl::Status CheckWhole(const actor::SlotRollout& data, const actor::SlotRolloutShape& shape) {
  DCS_RETURN_IF_ERROR(actor::CheckSlotRollout(data, shape));
  const int input_size = static_cast<int>(shape.input);
  const int action_size = static_cast<int>(shape.action);
  DCS_RETURN_IF_ERROR(CheckFinite("inputs", data.inputs, input_size));
  DCS_RETURN_IF_ERROR(CheckFinite("actions", data.actions, action_size));
  DCS_RETURN_IF_ERROR(CheckFinite("rewards", data.rewards, 1));
  DCS_RETURN_IF_ERROR(CheckFinite("last_input", data.last_input, input_size));
  for (const actor::Rollout::Truncation& cut : data.truncations) {
    DCS_RETURN_IF_ERROR(CheckFinite("a truncation's input", cut.input, input_size));
  }
  if (data.journal.actions.size() % action_size != 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "the journal has ", data.journal.actions.size(), " action values, not a multiple of ",
        action_size));
  }
  return absl::OkStatus();
}

}  // namespace

RunHost::RunHost(std::unique_ptr<TrainingSession> session, Evaluator evaluator,
                 actor::SlotRolloutShape shape)
    : session_(std::move(session)),
      evaluator_(std::move(evaluator)),
      n_envs_(session_->spec().n_envs),
      shape_(shape),
      start_(absl::Now()),
      first_timesteps_(session_->state().timesteps),
      epochs_(n_envs_, 0),
      pending_(n_envs_) {}

RunHost::~RunHost() { Stop(); }

void RunHost::Publish() {
  auto weights = std::make_shared<const actor::PolicyWeights>(session_->ActorWeights());
  {
    absl::MutexLock lock(&mu_);
    rollout_ = session_->state().rollouts;
    start_timesteps_ = session_->state().timesteps;
    weights_ = std::move(weights);
    published_at_ = absl::Now();
    journals_ = session_->state().journals;
    complete_ = session_->complete();
    // The slots' parts are learnt from: freeing them releases the slots waiting for new work.
    for (std::optional<actor::SlotRollout>& part : pending_) part.reset();
    pending_count_ = 0;
  }
  if (changed_) changed_();
}

absl::Status RunHost::CheckEpoch(int slot, int64_t epoch) {
  if (slot < 0 || slot >= n_envs_) {
    return absl::InvalidArgumentError(
        absl::StrCat("slot ", slot, " is not a slot of the run (n_envs ", n_envs_, ")"));
  }
  if (epoch < epochs_[slot]) {
    return absl::FailedPreconditionError(absl::StrCat("slot ", slot, "'s lease moved to epoch ",
                                                      epochs_[slot], "; this holder has epoch ",
                                                      epoch));
  }
  epochs_[slot] = epoch;
  return absl::OkStatus();
}

absl::StatusOr<SlotWork> RunHost::GetSlotWork(int slot, int64_t epoch, int64_t positioned_at,
                                              absl::Duration wait) {
  absl::MutexLock lock(&mu_);
  DCS_RETURN_IF_ERROR(CheckEpoch(slot, epoch));
  // The slot's part of the current rollout is in: its next work comes with the update.
  auto answerable = [this, slot]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
    return !pending_[slot].has_value() || stop_.HasBeenNotified() || complete_;
  };
  mu_.AwaitWithTimeout(absl::Condition(&answerable), wait);
  SlotWork work{.run_complete = complete_, .n_steps = shape_.num_steps};
  if (complete_ || pending_[slot].has_value()) return work;
  work.ready = true;
  work.rollout = rollout_;
  work.start_timesteps = start_timesteps_;
  work.weights = weights_;
  work.published_at = published_at_;
  if (positioned_at != rollout_) work.journal = journals_[slot];
  return work;
}

absl::StatusOr<bool> RunHost::PushRollout(int64_t epoch, int64_t rollout, int64_t policy_version,
                                          actor::SlotRollout data) {
  const int slot = data.slot;
  if (policy_version != rollout) {
    return absl::FailedPreconditionError(absl::StrCat(
        "rollout ", rollout, " is collected with policy version ", rollout, ", not ",
        policy_version));
  }
  DCS_RETURN_IF_ERROR(CheckWhole(data, shape_));
  absl::MutexLock lock(&mu_);
  DCS_RETURN_IF_ERROR(CheckEpoch(slot, epoch));
  if (rollout < rollout_ || (rollout == rollout_ && pending_[slot].has_value())) return true;
  if (rollout > rollout_ || complete_) {
    return absl::FailedPreconditionError(absl::StrCat(
        "rollout ", rollout, " is not being collected: ",
        complete_ ? "the run is complete" : absl::StrCat("rollout ", rollout_, " is")));
  }
  pending_[slot] = std::move(data);
  ++pending_count_;
  return false;
}

void RunHost::StartEvaluation(const EvaluationDue& due) {
  std::shared_ptr<const actor::PolicyWeights> weights;
  {
    absl::MutexLock lock(&mu_);
    weights = weights_;  // the current version: the one `due` names
  }
  evaluations_.push_back(
      {.due = due,
       .result = std::async(std::launch::async, [this, due, weights = std::move(weights)] {
         // The spec and plan are constant.
         return evaluator_({.spec = session_->spec(),
                            .plan = session_->plan(),
                            .due = due,
                            .weights = weights},
                           stop_);
       })});
}

absl::Status RunHost::RecordEvaluations(bool wait) {
  while (!evaluations_.empty()) {
    PendingEvaluation& next = evaluations_.front();
    if (!wait &&
        next.result.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      break;
    }
    DCS_ASSIGN_OR_RETURN(const actor::EvaluationResult result, next.result.get());
    session_->RecordEvaluation(next.due, result);
    evaluations_.pop_front();
  }
  return absl::OkStatus();
}

absl::StatusOr<HostStep> RunHost::Step() {
  std::vector<actor::SlotRollout> parts;
  {
    absl::MutexLock lock(&mu_);
    auto ready = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
      return stop_.HasBeenNotified() || pending_count_ == n_envs_;
    };
    mu_.Await(absl::Condition(&ready));
    if (stop_.HasBeenNotified()) return absl::CancelledError("the run host was stopped");
    for (std::optional<actor::SlotRollout>& part : pending_) parts.push_back(*std::move(part));
  }
  DCS_ASSIGN_OR_RETURN(actor::MergedRollout merged, actor::MergeSlotRollouts(std::move(parts)));
  const int64_t episodes = static_cast<int64_t>(merged.finished.size());
  DCS_ASSIGN_OR_RETURN(const std::optional<EvaluationDue> due,
                       session_->AddRollout(std::move(merged.rollout), merged.finished,
                                            std::move(merged.journals)));
  if (due.has_value()) StartEvaluation(*due);
  DCS_ASSIGN_OR_RETURN(const SessionUpdate update, session_->Update());
  Publish();
  if (update.final_evaluation.has_value()) StartEvaluation(*update.final_evaluation);
  // A checkpoint waits for the evaluations outstanding; when the next one falls due before
  // they are in (evaluations lag behind training), training waits for them instead, so a
  // checkpoint is never more than one evaluation interval late.
  const bool wait = session_->complete() || (checkpoint_wanted_ && session_->checkpoint_due());
  if (session_->checkpoint_due()) checkpoint_wanted_ = true;
  DCS_RETURN_IF_ERROR(RecordEvaluations(wait));

  const run::RunState& state = session_->state();
  const double seconds = absl::ToDoubleSeconds(absl::Now() - start_);
  HostStep step{
      .progress = {.timesteps = state.timesteps,
                   .total_timesteps = session_->spec().total_timesteps,
                   .updates = session_->policy_version(),
                   .steps_per_second =
                       static_cast<double>(state.timesteps - first_timesteps_) / seconds,
                   .recent_return = session_->recent_return(),
                   .recent_episode_length = session_->recent_episode_length(),
                   .update = update.stats,
                   .evaluation = state.evaluations.empty() ? nullptr : &state.evaluations.back()},
      .steps = static_cast<int64_t>(n_envs_) * shape_.num_steps,
      .episodes = episodes,
      .complete = session_->complete()};
  if (checkpoint_wanted_ && evaluations_.empty()) {
    DCS_ASSIGN_OR_RETURN(step.checkpoint, session_->Checkpoint());
    step.evaluation_log = session_->EvaluationLog();
    checkpoint_wanted_ = false;
  }
  return step;
}

void RunHost::Stop() {
  {
    // Under mu_: waiters re-check their conditions when it is released.
    absl::MutexLock lock(&mu_);
    if (stop_.HasBeenNotified()) return;
    stop_.Notify();
  }
  if (changed_) changed_();
}

}  // namespace dcs::learner
