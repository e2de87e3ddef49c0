// Copyright 2026 The DCS Authors.
#include "coordinator/study_sweep_driver.h"

#include <utility>

#include "common/status_macros.h"

namespace dcs::coordinator {

StudySweepDriver::StudySweepDriver(Store& store, std::string data_dir, CompletedRunLogs& logs)
    : store_(store), data_dir_(std::move(data_dir)), logs_(logs) {}

void StudySweepDriver::Adopt(const std::string& sweep_id, StudySweepSpec spec) {
  absl::MutexLock lock(&mu_);
  specs_.try_emplace(sweep_id, std::move(spec));
}

absl::StatusOr<const StudySweepSpec*> StudySweepDriver::SpecOf(const SweepRecord& sweep) {
  {
    absl::MutexLock lock(&mu_);
    if (auto kept = specs_.find(sweep.id); kept != specs_.end()) return &kept->second;
  }
  // Checked when it was submitted: only a store written by another version fails here.
  DCS_ASSIGN_OR_RETURN(StudySweepSpec spec, ParseStudySweepYaml(sweep.spec, sweep.name));
  absl::MutexLock lock(&mu_);
  return &specs_.try_emplace(sweep.id, std::move(spec)).first->second;
}

absl::StatusOr<std::vector<StudySweepDriver::SweepTick>> StudySweepDriver::Tick(absl::Time now) {
  DCS_ASSIGN_OR_RETURN(const std::vector<SweepRecord> sweeps, store_.sweeps().ListOpenSweeps());
  std::vector<SweepTick> ticks;
  for (const SweepRecord& sweep : sweeps) {
    absl::StatusOr<const StudySweepSpec*> spec = SpecOf(sweep);
    if (!spec.ok()) {
      ticks.push_back({.sweep_id = sweep.id, .step = spec.status()});
      continue;
    }
    absl::StatusOr<StudySweepStep> step =
        AdvanceStudySweep(store_, data_dir_, logs_, sweep, **spec, now);
    if (step.ok() && step->closed) {
      absl::MutexLock lock(&mu_);
      specs_.erase(sweep.id);
    }
    ticks.push_back({.sweep_id = sweep.id, .step = std::move(step)});
  }
  return ticks;
}

}  // namespace dcs::coordinator
