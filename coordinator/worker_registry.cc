// Copyright 2026 The DCS Authors.
#include "coordinator/worker_registry.h"

#include <algorithm>
#include <tuple>
#include <utility>

#include "absl/strings/str_cat.h"

namespace dcs::coordinator {

absl::string_view WorkerStateName(WorkerState state) {
  switch (state) {
    case WorkerState::kAlive: return "alive";
    case WorkerState::kLost: return "lost";
  }
  return "unknown";
}

absl::StatusOr<std::unique_ptr<WorkerRegistry>> WorkerRegistry::Create(
    WorkerRegistryOptions options) {
  if (options.heartbeat_interval <= absl::ZeroDuration()) {
    return absl::InvalidArgumentError(absl::StrCat(
        "heartbeat interval must be positive, got ", absl::FormatDuration(options.heartbeat_interval)));
  }
  if (options.lost_after < 2 * options.heartbeat_interval) {
    return absl::InvalidArgumentError(absl::StrCat(
        "worker timeout (", absl::FormatDuration(options.lost_after),
        ") must be at least twice the heartbeat interval (",
        absl::FormatDuration(options.heartbeat_interval), ")"));
  }
  if (options.forget_after <= options.lost_after) {
    return absl::InvalidArgumentError(absl::StrCat(
        "forget-after (", absl::FormatDuration(options.forget_after),
        ") must exceed the worker timeout (", absl::FormatDuration(options.lost_after), ")"));
  }
  return std::unique_ptr<WorkerRegistry>(new WorkerRegistry(options));
}

absl::StatusOr<std::string> WorkerRegistry::Register(WorkerInfo info, absl::Time now) {
  if (info.address.empty()) {
    return absl::InvalidArgumentError("a worker must register with the address it serves on");
  }
  absl::MutexLock lock(&mu_);
  ForgetSilentLocked(now);
  const int64_t sequence = next_sequence_++;
  std::string id = absl::StrCat(WorkerRoleName(info.role), "-", sequence);
  workers_[id] = Entry{sequence, WorkerRecord{.id = id,
                                              .info = std::move(info),
                                              .state = WorkerState::kAlive,
                                              .registered_at = now,
                                              .last_heartbeat_at = now}};
  return id;
}

absl::Status WorkerRegistry::Heartbeat(absl::string_view id, absl::Time now) {
  absl::MutexLock lock(&mu_);
  ForgetSilentLocked(now);
  auto it = workers_.find(id);
  if (it == workers_.end()) {
    return absl::NotFoundError(absl::StrCat("unknown worker '", id, "'; register again"));
  }
  it->second.record.last_heartbeat_at = now;
  return absl::OkStatus();
}

absl::Status WorkerRegistry::Unregister(absl::string_view id, absl::Time now) {
  absl::MutexLock lock(&mu_);
  ForgetSilentLocked(now);
  if (workers_.erase(id) == 0) {
    return absl::NotFoundError(absl::StrCat("unknown worker '", id, "'"));
  }
  return absl::OkStatus();
}

std::vector<WorkerRecord> WorkerRegistry::List(absl::Time now) const {
  std::vector<std::pair<int64_t, WorkerRecord>> listed;
  {
    absl::MutexLock lock(&mu_);
    listed.reserve(workers_.size());
    for (const auto& [id, entry] : workers_) {
      const absl::Duration silence = now - entry.record.last_heartbeat_at;
      if (silence >= options_.forget_after) continue;
      WorkerRecord record = entry.record;
      record.state = silence >= options_.lost_after ? WorkerState::kLost : WorkerState::kAlive;
      listed.emplace_back(entry.sequence, std::move(record));
    }
  }
  std::sort(listed.begin(), listed.end(), [](const auto& a, const auto& b) {
    return std::tie(a.second.info.role, a.first) < std::tie(b.second.info.role, b.first);
  });
  std::vector<WorkerRecord> records;
  records.reserve(listed.size());
  for (auto& [sequence, record] : listed) records.push_back(std::move(record));
  return records;
}

void WorkerRegistry::ForgetSilentLocked(absl::Time now) {
  absl::erase_if(workers_, [&](const auto& item) {
    return now - item.second.record.last_heartbeat_at >= options_.forget_after;
  });
}

}  // namespace dcs::coordinator
