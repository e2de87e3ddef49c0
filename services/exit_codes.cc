// Copyright 2026 The DCS Authors.
#include "services/exit_codes.h"

#include "absl/strings/cord.h"

namespace dcs::services {
namespace {

// Marks a UsageError; printed errors leave payloads out (services/cli/cli_command.h).
constexpr char kUsagePayload[] = "type.dcs.dev/dcs.Usage";

}  // namespace

int ExitCodeFor(const absl::Status& status) {
  switch (status.code()) {
    case absl::StatusCode::kInvalidArgument:
      return status.GetPayload(kUsagePayload).has_value() ? kExitUsage : kExitDataError;
    case absl::StatusCode::kNotFound: return kExitNoInput;
    case absl::StatusCode::kUnavailable:
    case absl::StatusCode::kDeadlineExceeded: return kExitUnavailable;
    case absl::StatusCode::kUnauthenticated:
    case absl::StatusCode::kPermissionDenied: return kExitNoPermission;
    default: return kExitFailure;
  }
}

absl::Status UsageError(absl::string_view message) {
  absl::Status status = absl::InvalidArgumentError(message);
  status.SetPayload(kUsagePayload, absl::Cord());
  return status;
}

}  // namespace dcs::services
