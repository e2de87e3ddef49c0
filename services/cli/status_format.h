// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_STATUS_FORMAT_H_
#define DCS_SERVICES_CLI_STATUS_FORMAT_H_

// How `dcs status` shows the coordinator's view of the cluster: a table for people, its rows as
// CSV, or the GetClusterStatusResponse as one line of JSON (command_output.h). Thread-safe
// (pure functions).

#include <string>

#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "services/cli/command_output.h"

namespace dcs::services::cli {

// Ages ("last heartbeat 0.4s ago") are computed against `now`.
std::string FormatClusterStatus(const v1::GetClusterStatusResponse& status,
                                const std::string& coordinator_address, absl::Time now,
                                OutputFormat format);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_STATUS_FORMAT_H_
