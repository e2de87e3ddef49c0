// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_RECORD_PROTO_H_
#define DCS_SERVICES_COORDINATOR_RECORD_PROTO_H_

// Conversions between the coordinator's records (runs and their states, sweeps, evaluation
// jobs, run files: coordinator/run_table.h, evaluation_table.h, sweep_table.h, run_files.h;
// workers: coordinator/worker_registry.h) and dcs.v1 messages. What workers send and read is
// services/run_proto.h's. Thread-safe (pure functions).

#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/evaluation_table.h"
#include "coordinator/run_files.h"
#include "coordinator/run_state.h"
#include "coordinator/run_table.h"
#include "coordinator/sweep_table.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/cluster.pb.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "dcs/v1/run.pb.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::services {

v1::RunState RunStateToProto(coordinator::RunState state);
// INVALID_ARGUMENT for RUN_STATE_UNSPECIFIED or an unknown value.
absl::StatusOr<coordinator::RunState> RunStateFromProto(v1::RunState state);

v1::Run RunToProto(const coordinator::RunRecord& run);
v1::Sweep SweepToProto(const coordinator::SweepRecord& sweep);

v1::EvaluationJob EvaluationJobToProto(const coordinator::EvaluationJobKey& key);
// INVALID_ARGUMENT for a job without a run id.
absl::StatusOr<coordinator::EvaluationJobKey> EvaluationJobFromProto(
    const v1::EvaluationJob& proto);

// `files` in pieces (services/pieces.h), each file's in order.
std::vector<v1::RunFile> RunFilesToPieces(const std::vector<coordinator::RunFile>& files);

v1::Worker WorkerToProto(const coordinator::WorkerRecord& record);

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_RECORD_PROTO_H_
