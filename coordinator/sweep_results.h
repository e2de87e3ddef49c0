// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SWEEP_RESULTS_H_
#define DCS_COORDINATOR_SWEEP_RESULTS_H_

// What a sweep's completed runs evaluated to, gathered from their directories in the
// coordinator's data directory (coordinator/run_files.h), as reports and figures read it
// (v1::SweepResults).

#include <string>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_map.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "coordinator/run_store.h"
#include "dcs/v1/evaluation.pb.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::coordinator {

// The evaluation logs of completed runs, each read once from its run's directory in
// `data_dir` and then kept: a completed run's log never changes, and reading a log's JSON is
// most of what a report costs (about 3 ms a run). The episodes' returns are left out: they are
// the bulk of a log and no report reads them. Thread-safe.
class CompletedRunLogs {
 public:
  explicit CompletedRunLogs(std::string data_dir) : data_dir_(std::move(data_dir)) {}

  // The log of `run`. REQUIRES: the run completed. DATA_LOSS naming the run if its log is
  // missing or unreadable.
  absl::StatusOr<v1::EvaluationLog> Get(const RunRecord& run) ABSL_LOCKS_EXCLUDED(mu_);

 private:
  const std::string data_dir_;
  absl::Mutex mu_;
  absl::flat_hash_map<std::string, v1::EvaluationLog> logs_ ABSL_GUARDED_BY(mu_);
};

// Each trial of `sweep` with the logs of its completed runs among `runs` (the sweep's, any
// order), in seed order. Errors as CompletedRunLogs::Get.
absl::StatusOr<v1::SweepResults> CollectSweepResults(const SweepRecord& sweep,
                                                     const std::vector<RunRecord>& runs,
                                                     CompletedRunLogs& logs);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SWEEP_RESULTS_H_
