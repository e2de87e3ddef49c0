// Copyright 2026 The DCS Authors.
#include "services/exit_codes.h"

namespace dcs::services {

int ExitCodeFor(const absl::Status& status) {
  switch (status.code()) {
    case absl::StatusCode::kInvalidArgument: return kExitDataError;
    case absl::StatusCode::kUnavailable:
    case absl::StatusCode::kDeadlineExceeded: return kExitUnavailable;
    case absl::StatusCode::kUnauthenticated:
    case absl::StatusCode::kPermissionDenied: return kExitNoPermission;
    default: return kExitFailure;
  }
}

}  // namespace dcs::services
