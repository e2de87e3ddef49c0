// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_GRPC_STATUS_H_
#define DCS_SERVICES_GRPC_STATUS_H_

// The only two conversions between absl::Status (libraries) and grpc::Status (the wire).
// The codes are the same google.rpc.Code values; grpc_status.cc checks that they agree.
// Thread-safe (pure functions).

#include <grpcpp/support/status.h>

#include "absl/status/status.h"

namespace dcs::services {

grpc::Status ToGrpcStatus(const absl::Status& status);
absl::Status FromGrpcStatus(const grpc::Status& status);

}  // namespace dcs::services

#endif  // DCS_SERVICES_GRPC_STATUS_H_
