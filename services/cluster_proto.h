// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLUSTER_PROTO_H_
#define DCS_SERVICES_CLUSTER_PROTO_H_

// Conversions between what a worker says about itself (common/worker_info.h), a build's
// versions, and dcs.v1 cluster messages. Thread-safe (pure functions).

#include "absl/status/statusor.h"
#include "common/worker_info.h"
#include "dcs/v1/cluster.pb.h"
#include "services/build_info.h"

namespace dcs::services {

v1::BuildInfo BuildInfoToProto(const BuildInfo& build);

v1::WorkerInfo WorkerInfoToProto(const WorkerInfo& info);

// INVALID_ARGUMENT if the role is WORKER_ROLE_UNSPECIFIED or unknown.
absl::StatusOr<WorkerInfo> WorkerInfoFromProto(const v1::WorkerInfo& proto);

}  // namespace dcs::services

#endif  // DCS_SERVICES_CLUSTER_PROTO_H_
