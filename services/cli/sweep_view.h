// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_SWEEP_VIEW_H_
#define DCS_SERVICES_CLI_SWEEP_VIEW_H_

// What `dcs watch` and `dcs sweeps` show of a sweep: its runs counted by state, overall and per
// trial (condition and mode), its environment steps per second and the time left at that pace,
// and the best trial so far (the highest IQM of its completed runs' last avg_combined).
// Thread-safe (pure functions).

#include <string>
#include <vector>

#include "dcs/v1/coordinator_service.pb.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::services::cli {

// One line: "sweep-3 quickstart: running, 7/18 runs done (2 running, 9 queued, 0 failed),
// 23400 steps/s, ETA 3m10s, best: sinusoidal (live) 468.2".
std::string SweepHeadline(const v1::GetSweepResponse& sweep);

// The headline, then a table with a row per trial: CONDITION, MODE, DONE (completed/seeds),
// RUNNING, QUEUED, FAILED, LAST (IQM of its completed runs' last avg_combined, "-" before one).
std::string SweepProgressView(const v1::GetSweepResponse& sweep);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_SWEEP_VIEW_H_
