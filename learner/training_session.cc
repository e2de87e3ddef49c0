// Copyright 2026 The DCS Authors.
#include "learner/training_session.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "run/evaluation_log.h"

namespace dcs::learner {
namespace {

constexpr size_t kRecentEpisodes = 100;  // SB3's ep_info_buffer

// Drops all but the last `count` of `values`.
template <typename T>
void KeepLast(size_t count, std::vector<T>& values) {
  if (values.size() > count) values.erase(values.begin(), values.end() - count);
}

// The mean of `values`; NaN if there are none.
template <typename T>
double MeanOrNaN(const std::vector<T>& values) {
  if (values.empty()) return std::nan("");
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

}  // namespace

absl::StatusOr<std::unique_ptr<TrainingSession>> TrainingSession::Create(
    run::RunSpec spec, run::RunPlan plan, const run::PolicySpec& policy,
    const std::vector<env::StateProjection>& projections, const run::Checkpoint* checkpoint) {
  std::vector<env::StateProjection> coverage_projections;
  if (spec.coverage.has_value()) {
    DCS_ASSIGN_OR_RETURN(coverage_projections, run::SelectProjections(*spec.coverage, projections));
  }
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<PpoLearner> learner,
                       PpoLearner::Create(policy, spec.ppo, spec.n_envs, spec.seed));
  std::unique_ptr<TrainingSession> session(new TrainingSession(
      std::move(spec), std::move(plan), std::move(coverage_projections), std::move(learner)));
  if (checkpoint == nullptr) {
    // Every slot stands at the reset of its first episode; no cell is visited yet.
    session->state_.journals.resize(session->spec_.n_envs);
    session->state_.coverage = run::NewCoverage(session->coverage_projections_);
    return session;
  }
  DCS_RETURN_IF_ERROR(session->learner_->LoadState(checkpoint->learner));
  const int n_envs = session->spec_.n_envs;
  if (static_cast<int>(checkpoint->state.journals.size()) != n_envs) {
    return absl::FailedPreconditionError(
        absl::StrCat("checkpoint ", checkpoint->name, " has ", checkpoint->state.journals.size(),
                     " environment slots, the run has n_envs ", n_envs));
  }
  if (!std::equal(session->coverage_projections_.begin(), session->coverage_projections_.end(),
                  checkpoint->state.coverage.begin(), checkpoint->state.coverage.end(),
                  [](const env::StateProjection& projection, const run::ProjectionCounts& counts) {
                    return projection.name == counts.projection &&
                           env::NumCells(projection) == counts.cells;
                  })) {
    return absl::FailedPreconditionError(absl::StrCat(
        "checkpoint ", checkpoint->name, " counts coverage in other projections than the run"));
  }
  session->state_ = checkpoint->state;
  return session;
}

TrainingSession::TrainingSession(run::RunSpec spec, run::RunPlan plan,
                                 std::vector<env::StateProjection> coverage_projections,
                                 std::unique_ptr<PpoLearner> learner)
    : spec_(std::move(spec)),
      plan_(std::move(plan)),
      evaluation_steps_(run::EvaluationSteps(spec_, plan_)),
      coverage_projections_(std::move(coverage_projections)),
      learner_(std::move(learner)) {}

absl::StatusOr<std::optional<EvaluationDue>> TrainingSession::AddRollout(
    actor::Rollout rollout, std::span<const actor::EpisodeSummary> finished,
    std::vector<actor::SlotJournal> journals) {
  if (complete()) {
    return absl::FailedPreconditionError(absl::StrCat(
        "the run is complete (", state_.timesteps, " of ", spec_.total_timesteps, " steps)"));
  }
  if (waiting_.has_value()) {
    return absl::FailedPreconditionError(
        absl::StrCat("rollout ", state_.rollouts, " waits for its update"));
  }
  if (rollout.num_steps != spec_.ppo.n_steps || rollout.num_envs != spec_.n_envs ||
      static_cast<int>(journals.size()) != spec_.n_envs) {
    return absl::InvalidArgumentError(absl::StrCat(
        "rollout ", state_.rollouts, " has ", rollout.num_steps, " steps of ", rollout.num_envs,
        " slots and ", journals.size(), " journals; the run takes ", spec_.ppo.n_steps,
        " steps of each of its ", spec_.n_envs, " slots"));
  }
  for (const actor::EpisodeSummary& episode : finished) {
    state_.recent_returns.push_back(episode.episode_return);
    state_.recent_lengths.push_back(episode.length);
  }
  KeepLast(kRecentEpisodes, state_.recent_returns);
  KeepLast(kRecentEpisodes, state_.recent_lengths);
  state_.journals = std::move(journals);
  waiting_from_ = state_.timesteps;
  if (spec_.coverage.has_value()) {
    run::RecordCoverage(coverage_projections_, spec_.coverage->window, rollout, waiting_from_,
                        state_.coverage);
  }
  state_.timesteps += static_cast<int64_t>(rollout.num_steps) * rollout.num_envs;
  waiting_ = std::move(rollout);
  checkpoint_due_ = false;

  EvaluationDue due{.policy_version = policy_version()};
  for (int64_t step : evaluation_steps_) {
    if (step > waiting_from_ && step <= state_.timesteps) due.steps.push_back(step);
  }
  waiting_reached_evaluation_ = !due.steps.empty();
  if (!waiting_reached_evaluation_) return std::nullopt;
  return due;
}

absl::StatusOr<SessionUpdate> TrainingSession::Update() {
  if (!waiting_.has_value()) {
    return absl::FailedPreconditionError("no rollout waits for an update");
  }
  absl::StatusOr<UpdateStats> stats = learner_->Update(*waiting_);
  if (!stats.ok()) {
    return absl::Status(stats.status().code(),
                        absl::StrCat("environment steps ", waiting_from_, " to ", state_.timesteps,
                                     ": ", stats.status().message()));
  }
  waiting_.reset();
  ++state_.rollouts;
  checkpoint_due_ = waiting_reached_evaluation_ || complete();
  SessionUpdate update{.stats = *stats};
  if (complete()) {
    update.final_evaluation =
        EvaluationDue{.steps = {state_.timesteps}, .policy_version = policy_version()};
  }
  return update;
}

void TrainingSession::RecordEvaluation(const EvaluationDue& due,
                                       const actor::EvaluationResult& result) {
  for (int64_t step : due.steps) {
    actor::EvaluationResult recorded = result;
    recorded.step = step;
    recorded.updates = due.policy_version;
    state_.evaluations.push_back(std::move(recorded));
  }
}

absl::StatusOr<run::Checkpoint> TrainingSession::Checkpoint() const {
  DCS_ASSIGN_OR_RETURN(std::string learner, learner_->SaveState());
  return run::Checkpoint{
      .name = run::CheckpointName(state_.timesteps),
      .state = state_,
      .learner = std::move(learner)};
}

v1::EvaluationLog TrainingSession::EvaluationLog() const {
  v1::EvaluationLog log =
      run::MakeEvaluationLog(spec_, state_.evaluations, plan_.stage_boundaries, complete());
  if (spec_.coverage.has_value()) {
    run::AppendCoverage(state_.coverage, spec_.coverage->window, state_.timesteps, log);
  }
  return log;
}

double TrainingSession::recent_return() const { return MeanOrNaN(state_.recent_returns); }

double TrainingSession::recent_episode_length() const {
  return MeanOrNaN(state_.recent_lengths);
}

}  // namespace dcs::learner
