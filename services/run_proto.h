// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_RUN_PROTO_H_
#define DCS_SERVICES_RUN_PROTO_H_

// Conversions between what a run's workers and the coordinator tell each other (leases,
// progress, evaluation returns: run/lease_key.h, run/worker_reports.h; checkpoints) and dcs.v1
// messages. The coordinator's own records go to the wire by services/coordinator/record_proto.h.
// Thread-safe (pure functions).

#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "dcs/v1/run.pb.h"
#include "run/lease_key.h"
#include "run/run_checkpoint.h"
#include "run/worker_reports.h"
#include "services/pieces.h"

namespace dcs::services {

// True once nothing moves the run (the sweep) any more: completed, failed or cancelled.
bool RunEnded(v1::RunState state);
bool SweepEnded(v1::SweepState state);

v1::Lease LeaseToProto(const run::LeaseKey& key);
// INVALID_ARGUMENT for a lease without a run id.
absl::StatusOr<run::LeaseKey> LeaseFromProto(const v1::Lease& proto);

v1::ContextReturns ContextReturnsToProto(const run::ContextReturns& returns);
run::ContextReturns ContextReturnsFromProto(const v1::ContextReturns& proto);

// Streams carry files and checkpoints in pieces (services/pieces.h); a streamed checkpoint may
// hold up to kMaxStreamedBytes.

// `checkpoint` in pieces: the first names it; each carries the next bytes of both files.
std::vector<v1::CheckpointPiece> CheckpointToPieces(const run::PackedCheckpoint& checkpoint);

// Adds the next piece of a streamed checkpoint to `checkpoint`; the first (`first`) names it.
// INVALID_ARGUMENT for a first piece without a name, or a later one naming another checkpoint;
// RESOURCE_EXHAUSTED once its files pass kMaxStreamedBytes.
absl::Status AddCheckpointPiece(const v1::CheckpointPiece& piece, bool first,
                                run::PackedCheckpoint& checkpoint);

v1::RunProgress ProgressToProto(const run::RunProgress& progress, int64_t total_timesteps);
run::RunProgress ProgressFromProto(const v1::RunProgress& proto);

}  // namespace dcs::services

#endif  // DCS_SERVICES_RUN_PROTO_H_
