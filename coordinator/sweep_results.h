// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SWEEP_RESULTS_H_
#define DCS_COORDINATOR_SWEEP_RESULTS_H_

// What a sweep's completed runs evaluated to, gathered from their directories in the
// coordinator's data directory (coordinator/run_files.h), as reports and figures read it
// (v1::SweepResults). Thread-compatible: reads files a run's learner no longer writes.

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "coordinator/run_store.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::coordinator {

// Each trial of `sweep` with the evaluation logs of its completed runs among `runs` (the
// sweep's, any order), in seed order, the episodes' returns left out (they are the bulk of a
// log and no report reads them). DATA_LOSS naming the run for a completed run whose log is
// missing or unreadable.
absl::StatusOr<v1::SweepResults> CollectSweepResults(const SweepRecord& sweep,
                                                     const std::vector<RunRecord>& runs,
                                                     absl::string_view data_dir);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SWEEP_RESULTS_H_
