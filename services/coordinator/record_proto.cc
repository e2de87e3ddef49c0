// Copyright 2026 The DCS Authors.
#include "services/coordinator/record_proto.h"

#include <iterator>
#include <utility>

#include "absl/strings/str_cat.h"
#include "services/cluster_proto.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

struct StateMapping {
  coordinator::RunState state;
  v1::RunState proto;
};

constexpr StateMapping kStates[] = {
    {coordinator::RunState::kQueued, v1::RUN_STATE_QUEUED},
    {coordinator::RunState::kRunning, v1::RUN_STATE_RUNNING},
    {coordinator::RunState::kCompleted, v1::RUN_STATE_COMPLETED},
    {coordinator::RunState::kFailed, v1::RUN_STATE_FAILED},
    {coordinator::RunState::kCancelled, v1::RUN_STATE_CANCELLED}};
static_assert(std::size(kStates) == std::size(coordinator::kRunStateNames));

}  // namespace

v1::RunState RunStateToProto(coordinator::RunState state) {
  for (const StateMapping& mapping : kStates) {
    if (mapping.state == state) return mapping.proto;
  }
  return v1::RUN_STATE_UNSPECIFIED;
}

absl::StatusOr<coordinator::RunState> RunStateFromProto(v1::RunState state) {
  for (const StateMapping& mapping : kStates) {
    if (mapping.proto == state) return mapping.state;
  }
  return absl::InvalidArgumentError(absl::StrCat("run state ", v1::RunState_Name(state),
                                                 " is not a state a run can be in"));
}

v1::Run RunToProto(const coordinator::RunRecord& run) {
  v1::Run proto;
  proto.set_run_id(run.id);
  proto.set_env(run.submission.env);
  proto.set_seed(run.submission.seed);
  proto.set_state(RunStateToProto(run.state));
  proto.set_error(run.error);
  *proto.mutable_progress() = ProgressToProto(run.progress, run.submission.total_timesteps);
  proto.set_checkpoint(run.checkpoint);
  proto.set_learner_numerics(run.learner_numerics);
  proto.set_actor_numerics(run.actor_numerics);
  *proto.mutable_create_time() = TimeToProto(run.created_at);
  *proto.mutable_update_time() = TimeToProto(run.updated_at);
  proto.set_sweep_id(run.sweep_id);
  if (run.trial.has_value()) proto.set_trial(*run.trial);
  return proto;
}

v1::Sweep SweepToProto(const coordinator::SweepRecord& sweep) {
  static constexpr std::pair<coordinator::SweepState, v1::SweepState> kSweepStates[] = {
      {coordinator::SweepState::kQueued, v1::SWEEP_STATE_QUEUED},
      {coordinator::SweepState::kRunning, v1::SWEEP_STATE_RUNNING},
      {coordinator::SweepState::kCompleted, v1::SWEEP_STATE_COMPLETED},
      {coordinator::SweepState::kFailed, v1::SWEEP_STATE_FAILED},
      {coordinator::SweepState::kCancelled, v1::SWEEP_STATE_CANCELLED}};
  v1::Sweep proto;
  proto.set_sweep_id(sweep.id);
  proto.set_name(sweep.name);
  for (const auto& [state, wire] : kSweepStates) {
    if (state == sweep.state) proto.set_state(wire);
  }
  proto.set_seeds(sweep.seeds);
  for (const coordinator::TrialRecord& trial : sweep.trials) {
    v1::Trial& out = *proto.add_trials();
    out.set_condition(trial.condition);
    out.set_family(trial.family);
    out.set_observe(trial.observe);
    if (trial.study_trial.has_value()) out.set_study_trial(*trial.study_trial);
    out.set_retrain(trial.retrain);
  }
  proto.set_study_id(sweep.study_id);
  proto.set_open(sweep.open);
  int64_t total = 0;
  for (const auto& [state, runs] : sweep.runs_by_state) {
    total += runs;
    const int32_t count = static_cast<int32_t>(runs);
    switch (state) {
      case coordinator::RunState::kQueued: proto.set_queued(count); break;
      case coordinator::RunState::kRunning: proto.set_running(count); break;
      case coordinator::RunState::kCompleted: proto.set_completed(count); break;
      case coordinator::RunState::kFailed: proto.set_failed(count); break;
      case coordinator::RunState::kCancelled: proto.set_cancelled(count); break;
    }
  }
  proto.set_runs(static_cast<int32_t>(total));
  *proto.mutable_create_time() = TimeToProto(sweep.created_at);
  *proto.mutable_update_time() = TimeToProto(sweep.updated_at);
  return proto;
}

v1::EvaluationJob EvaluationJobToProto(const coordinator::EvaluationJobKey& key) {
  v1::EvaluationJob proto;
  proto.set_run_id(key.run_id);
  proto.set_policy_version(key.policy_version);
  proto.set_context(key.context);
  proto.set_epoch(key.epoch);
  return proto;
}

absl::StatusOr<coordinator::EvaluationJobKey> EvaluationJobFromProto(
    const v1::EvaluationJob& proto) {
  if (proto.run_id().empty()) return absl::InvalidArgumentError("the job names no run");
  return coordinator::EvaluationJobKey{.run_id = proto.run_id(),
                                       .policy_version = proto.policy_version(),
                                       .context = proto.context(),
                                       .epoch = proto.epoch()};
}

std::vector<v1::RunFile> RunFilesToPieces(const std::vector<coordinator::RunFile>& files) {
  std::vector<v1::RunFile> pieces;
  for (const coordinator::RunFile& file : files) {
    for (absl::string_view bytes : SplitIntoPieces(file.contents)) {
      v1::RunFile& piece = pieces.emplace_back();
      piece.set_path(file.path);
      piece.set_contents(bytes.data(), bytes.size());
    }
  }
  return pieces;
}

v1::Worker WorkerToProto(const coordinator::WorkerRecord& record) {
  v1::Worker proto;
  proto.set_worker_id(record.id);
  *proto.mutable_info() = WorkerInfoToProto(record.info);
  proto.set_state(record.state == coordinator::WorkerState::kAlive ? v1::WORKER_STATE_ALIVE
                                                                   : v1::WORKER_STATE_LOST);
  *proto.mutable_registered_time() = TimeToProto(record.registered_at);
  *proto.mutable_last_heartbeat_time() = TimeToProto(record.last_heartbeat_at);
  return proto;
}

}  // namespace dcs::services
