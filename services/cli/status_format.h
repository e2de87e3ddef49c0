// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_STATUS_FORMAT_H_
#define DCS_SERVICES_CLI_STATUS_FORMAT_H_

// How `dcs status` shows the coordinator's view of the cluster: a table for people, or the
// GetClusterStatusResponse as JSON with proto field names (stable, for scripts).
// Thread-safe (pure functions).

#include <string>
#include <utility>
#include <vector>
#include "absl/strings/string_view.h"

#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.pb.h"

namespace dcs::services::cli {

enum class OutputFormat { kTable, kJson };

// The names the -o flag uses: "table", "json".
std::vector<std::pair<std::string, OutputFormat>> OutputFormatNames();

// Ages ("last heartbeat 0.4s ago") are computed against `now`.
std::string FormatClusterStatus(const v1::GetClusterStatusResponse& status,
                                const std::string& coordinator_address, absl::Time now,
                                OutputFormat format);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_STATUS_FORMAT_H_
