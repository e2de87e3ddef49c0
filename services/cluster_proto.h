// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLUSTER_PROTO_H_
#define DCS_SERVICES_CLUSTER_PROTO_H_

// Conversions between the coordinator's worker types and dcs.v1 cluster messages.
// Thread-safe (pure functions).

#include "absl/status/statusor.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/cluster.pb.h"
#include "services/build_info.h"

namespace dcs::services {

v1::BuildInfo BuildInfoToProto(const BuildInfo& build);

v1::WorkerInfo WorkerInfoToProto(const coordinator::WorkerInfo& info);

// INVALID_ARGUMENT if the role is WORKER_ROLE_UNSPECIFIED or unknown.
absl::StatusOr<coordinator::WorkerInfo> WorkerInfoFromProto(const v1::WorkerInfo& proto);

v1::Worker WorkerToProto(const coordinator::WorkerRecord& record);

}  // namespace dcs::services

#endif  // DCS_SERVICES_CLUSTER_PROTO_H_
