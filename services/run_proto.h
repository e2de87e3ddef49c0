// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_RUN_PROTO_H_
#define DCS_SERVICES_RUN_PROTO_H_

// Conversions between the coordinator's run, evaluation and sweep types
// (coordinator/run_table.h, evaluation_table.h, sweep_table.h, run_files.h) and dcs.v1
// messages. Thread-safe (pure functions).

#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "coordinator/run_files.h"
#include "coordinator/run_state.h"
#include "coordinator/evaluation_table.h"
#include "coordinator/sweep_table.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "dcs/v1/run.pb.h"
#include "dcs/v1/sweep.pb.h"
#include "run/run_checkpoint.h"
#include "services/pieces.h"

namespace dcs::services {

v1::RunState RunStateToProto(coordinator::RunState state);
// INVALID_ARGUMENT for RUN_STATE_UNSPECIFIED or an unknown value.
absl::StatusOr<coordinator::RunState> RunStateFromProto(v1::RunState state);

// True once nothing moves the run (the sweep) any more: completed, failed or cancelled.
bool RunEnded(v1::RunState state);
bool SweepEnded(v1::SweepState state);

v1::Run RunToProto(const coordinator::RunRecord& run);
v1::Sweep SweepToProto(const coordinator::SweepRecord& sweep);

v1::Lease LeaseToProto(const coordinator::LeaseKey& key);
// INVALID_ARGUMENT for a lease without a run id.
absl::StatusOr<coordinator::LeaseKey> LeaseFromProto(const v1::Lease& proto);

v1::EvaluationJob EvaluationJobToProto(const coordinator::EvaluationJobKey& key);
// INVALID_ARGUMENT for a job without a run id.
absl::StatusOr<coordinator::EvaluationJobKey> EvaluationJobFromProto(
    const v1::EvaluationJob& proto);

v1::ContextReturns ContextReturnsToProto(const coordinator::ContextReturns& returns);
coordinator::ContextReturns ContextReturnsFromProto(const v1::ContextReturns& proto);

// Streams carry files and checkpoints in pieces (services/pieces.h); a streamed checkpoint may
// hold up to kMaxStreamedBytes.

// `checkpoint` in pieces: the first names it; each carries the next bytes of both files.
std::vector<v1::CheckpointPiece> CheckpointToPieces(const run::PackedCheckpoint& checkpoint);

// Adds the next piece of a streamed checkpoint to `checkpoint`; the first (`first`) names it.
// INVALID_ARGUMENT for a first piece without a name, or a later one naming another checkpoint;
// RESOURCE_EXHAUSTED once its files pass kMaxStreamedBytes.
absl::Status AddCheckpointPiece(const v1::CheckpointPiece& piece, bool first,
                                run::PackedCheckpoint& checkpoint);

// `files` in pieces, each file's in order.
std::vector<v1::RunFile> RunFilesToPieces(const std::vector<coordinator::RunFile>& files);

v1::RunProgress ProgressToProto(const coordinator::RunProgress& progress,
                                int64_t total_timesteps);
coordinator::RunProgress ProgressFromProto(const v1::RunProgress& proto);

}  // namespace dcs::services

#endif  // DCS_SERVICES_RUN_PROTO_H_
