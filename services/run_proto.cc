// Copyright 2026 The DCS Authors.
#include "services/run_proto.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"

namespace dcs::services {
v1::RunProgress ProgressToProto(const run::RunProgress& progress, int64_t total_timesteps) {
  v1::RunProgress proto;
  proto.set_timesteps(progress.timesteps);
  proto.set_total_timesteps(total_timesteps);
  proto.set_policy_version(progress.policy_version);
  proto.set_steps_per_second(progress.steps_per_second);
  if (!std::isnan(progress.recent_return)) proto.set_recent_return(progress.recent_return);
  if (progress.avg_combined.has_value()) proto.set_avg_combined(*progress.avg_combined);
  if (progress.evaluation_step.has_value()) proto.set_evaluation_step(*progress.evaluation_step);
  return proto;
}

run::RunProgress ProgressFromProto(const v1::RunProgress& proto) {
  run::RunProgress progress{
      .timesteps = proto.timesteps(),
      .policy_version = proto.policy_version(),
      .steps_per_second = proto.steps_per_second(),
      .recent_return = proto.has_recent_return() ? proto.recent_return()
                                                 : std::numeric_limits<double>::quiet_NaN()};
  if (proto.has_avg_combined()) progress.avg_combined = proto.avg_combined();
  if (proto.has_evaluation_step()) progress.evaluation_step = proto.evaluation_step();
  return progress;
}

bool RunEnded(v1::RunState state) {
  return state == v1::RUN_STATE_COMPLETED || state == v1::RUN_STATE_FAILED ||
         state == v1::RUN_STATE_CANCELLED;
}

bool SweepEnded(v1::SweepState state) {
  return state == v1::SWEEP_STATE_COMPLETED || state == v1::SWEEP_STATE_FAILED ||
         state == v1::SWEEP_STATE_CANCELLED;
}

v1::Lease LeaseToProto(const run::LeaseKey& key) {
  v1::Lease proto;
  proto.set_run_id(key.run_id);
  proto.set_slot(key.slot);
  proto.set_epoch(key.epoch);
  return proto;
}

absl::StatusOr<run::LeaseKey> LeaseFromProto(const v1::Lease& proto) {
  if (proto.run_id().empty()) return absl::InvalidArgumentError("the lease names no run");
  return run::LeaseKey{.run_id = proto.run_id(), .slot = proto.slot(), .epoch = proto.epoch()};
}

v1::ContextReturns ContextReturnsToProto(const run::ContextReturns& returns) {
  v1::ContextReturns proto;
  proto.mutable_returns()->Assign(returns.returns.begin(), returns.returns.end());
  proto.set_seconds(returns.seconds);
  return proto;
}

run::ContextReturns ContextReturnsFromProto(const v1::ContextReturns& proto) {
  return {.returns = {proto.returns().begin(), proto.returns().end()},
          .seconds = proto.seconds()};
}

std::vector<v1::CheckpointPiece> CheckpointToPieces(const run::PackedCheckpoint& checkpoint) {
  const std::vector<absl::string_view> learner = SplitIntoPieces(checkpoint.learner);
  const std::vector<absl::string_view> run_state = SplitIntoPieces(checkpoint.run_state);
  std::vector<v1::CheckpointPiece> pieces(std::max(learner.size(), run_state.size()));
  pieces.front().set_name(checkpoint.name);
  pieces.front().set_learner_sha256(checkpoint.learner_sha256);
  pieces.front().set_run_state_sha256(checkpoint.run_state_sha256);
  for (size_t i = 0; i < learner.size(); ++i) pieces[i].set_learner(learner[i].data(), learner[i].size());
  for (size_t i = 0; i < run_state.size(); ++i) pieces[i].set_run_state(run_state[i].data(), run_state[i].size());
  return pieces;
}

absl::Status AddCheckpointPiece(const v1::CheckpointPiece& piece, bool first,
                                run::PackedCheckpoint& checkpoint) {
  if (first) {
    if (piece.name().empty()) {
      return absl::InvalidArgumentError("the first piece of a checkpoint names no checkpoint");
    }
    checkpoint = {.name = piece.name(),
                  .learner_sha256 = piece.learner_sha256(),
                  .run_state_sha256 = piece.run_state_sha256()};
  } else if (!piece.name().empty() && piece.name() != checkpoint.name) {
    return absl::InvalidArgumentError(absl::StrCat("a piece of checkpoint ", piece.name(),
                                                   " in the stream of checkpoint ",
                                                   checkpoint.name));
  }
  if (checkpoint.learner.size() + checkpoint.run_state.size() + piece.learner().size() +
          piece.run_state().size() >
      kMaxStreamedBytes) {
    return absl::ResourceExhaustedError(absl::StrCat("checkpoint ", checkpoint.name,
                                                     " is larger than ", kMaxStreamedBytes,
                                                     " bytes"));
  }
  checkpoint.learner.append(piece.learner());
  checkpoint.run_state.append(piece.run_state());
  return absl::OkStatus();
}

}  // namespace dcs::services
