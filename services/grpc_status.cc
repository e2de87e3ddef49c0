// Copyright 2026 The DCS Authors.
#include "services/grpc_status.h"

#include <string>

namespace dcs::services {
namespace {

#define DCS_CHECK_CODE(absl_code, grpc_code)                                      \
  static_assert(static_cast<int>(absl::StatusCode::absl_code) ==                  \
                    static_cast<int>(grpc::StatusCode::grpc_code),                \
                "absl::StatusCode::" #absl_code " != grpc::StatusCode::" #grpc_code)
DCS_CHECK_CODE(kOk, OK);
DCS_CHECK_CODE(kCancelled, CANCELLED);
DCS_CHECK_CODE(kUnknown, UNKNOWN);
DCS_CHECK_CODE(kInvalidArgument, INVALID_ARGUMENT);
DCS_CHECK_CODE(kDeadlineExceeded, DEADLINE_EXCEEDED);
DCS_CHECK_CODE(kNotFound, NOT_FOUND);
DCS_CHECK_CODE(kAlreadyExists, ALREADY_EXISTS);
DCS_CHECK_CODE(kPermissionDenied, PERMISSION_DENIED);
DCS_CHECK_CODE(kResourceExhausted, RESOURCE_EXHAUSTED);
DCS_CHECK_CODE(kFailedPrecondition, FAILED_PRECONDITION);
DCS_CHECK_CODE(kAborted, ABORTED);
DCS_CHECK_CODE(kOutOfRange, OUT_OF_RANGE);
DCS_CHECK_CODE(kUnimplemented, UNIMPLEMENTED);
DCS_CHECK_CODE(kInternal, INTERNAL);
DCS_CHECK_CODE(kUnavailable, UNAVAILABLE);
DCS_CHECK_CODE(kDataLoss, DATA_LOSS);
DCS_CHECK_CODE(kUnauthenticated, UNAUTHENTICATED);
#undef DCS_CHECK_CODE

}  // namespace

grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  return grpc::Status(static_cast<grpc::StatusCode>(status.code()),
                      std::string(status.message()));
}

absl::Status FromGrpcStatus(const grpc::Status& status) {
  if (status.ok()) return absl::OkStatus();
  return absl::Status(static_cast<absl::StatusCode>(status.error_code()),
                      status.error_message());
}

}  // namespace dcs::services
