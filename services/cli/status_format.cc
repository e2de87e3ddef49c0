// Copyright 2026 The DCS Authors.
#include "services/cli/status_format.h"

#include <algorithm>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/text_table.h"
#include "services/time_proto.h"

namespace dcs::services::cli {
namespace {

// "0.4s" under a minute, else whole seconds such as "2m5s".
std::string Age(absl::Time now, const google::protobuf::Timestamp& then) {
  const absl::Duration age = std::max(now - TimeFromProto(then), absl::ZeroDuration());
  if (age < absl::Minutes(1)) return absl::StrFormat("%.1fs", absl::ToDoubleSeconds(age));
  return absl::FormatDuration(absl::Trunc(age, absl::Seconds(1)));
}

}  // namespace

std::string FormatClusterStatus(const v1::GetClusterStatusResponse& status,
                                const std::string& coordinator_address, absl::Time now,
                                OutputFormat format) {
  if (format == OutputFormat::kJson) {
    return CommandJson(status) + "\n";
  }
  std::vector<std::vector<std::string>> rows = {
      {"ROLE", "ID", "ADDRESS", "STATE", "LAST HEARTBEAT", "HOST", "PID", "VERSION"}};
  for (const v1::Worker& worker : status.workers()) {
    rows.push_back({EnumWordOf(worker.info().role()), worker.worker_id(),
                    worker.info().address(), EnumWordOf(worker.state()),
                    Age(now, worker.last_heartbeat_time()) + " ago", worker.info().hostname(),
                    absl::StrCat(worker.info().pid()), worker.info().build().version()});
  }
  if (format == OutputFormat::kCsv) return FormatRows(rows, format);
  return absl::StrCat("coordinator  ", coordinator_address, "  version ",
                      status.coordinator_build().version(), "  up ",
                      Age(now, status.coordinator_start_time()), "\n",
                      status.workers().empty() ? "no workers\n" : "\n" + RenderTable(rows));
}

}  // namespace dcs::services::cli
