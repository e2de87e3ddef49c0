// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_REMOVAL_H_
#define DCS_COORDINATOR_RUN_REMOVAL_H_

// Ended runs and sweeps removed for good (`dcs runs rm`, `dcs sweeps rm`): from the store
// first, in one transaction, and then their directories in the data directory
// (coordinator/run_files.h). The store decides: a run is gone once its rows are, and no id
// is given twice, so a directory left by a crash between the two (or written by a learner's
// last checkpoint as its run went) is never read again; RemoveLeftoverRunDirectories, run at
// the coordinator's start, removes it. Thread-safe as the store is; a run's directory is
// touched only once its run is gone from the store.

#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "coordinator/run_table.h"
#include "coordinator/store.h"
#include "coordinator/sweep_table.h"

namespace dcs::coordinator {

struct RunRemoval {
  std::vector<RunRecord> runs;  // as they were (RunTable::DeleteRuns)
  // The first error removing their directories, which stay for the next start to remove; the
  // runs are gone all the same.
  absl::Status files;
};

struct SweepRemoval {
  std::vector<RemovedSweep> sweeps;  // as they were (SweepTable::DeleteSweeps)
  absl::Status files;                // as RunRemoval::files
};

// Removes the runs `run_ids` from `store` (errors as RunTable::DeleteRuns: nothing is removed
// then), then their directories in `data_dir`.
absl::StatusOr<RunRemoval> RemoveRuns(Store& store, absl::string_view data_dir,
                                      absl::Span<const std::string> run_ids);

// Removes the sweeps `sweep_ids` from `store` (errors as SweepTable::DeleteSweeps), then their
// runs' directories in `data_dir`.
absl::StatusOr<SweepRemoval> RemoveSweeps(Store& store, absl::string_view data_dir,
                                          absl::Span<const std::string> sweep_ids);

// Removes the directories in `data_dir` of runs removed from `store` (RunTable::RemovedRuns)
// and returns their run ids. Every other entry stays, such as the directory of a run newer
// than the store (one restored from an older backup). Errors: the store's, or the first
// directory that could not be read or removed, naming it.
absl::StatusOr<std::vector<std::string>> RemoveLeftoverRunDirectories(Store& store,
                                                                      absl::string_view data_dir);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_REMOVAL_H_
