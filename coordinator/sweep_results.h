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
#include "coordinator/sweep_table.h"
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
  // Drops the log of run `run_id`, if kept: the run was removed.
  void Forget(const std::string& run_id) ABSL_LOCKS_EXCLUDED(mu_);

 private:
  const std::string data_dir_;
  absl::Mutex mu_;
  absl::flat_hash_map<std::string, v1::EvaluationLog> logs_ ABSL_GUARDED_BY(mu_);
};

// Cuts `log` down to what a report reads (report/sweep_report.h): the last evaluation and
// the best-anytime one (best_anytime_index renumbered), each without its per-context results;
// the scores, the coverage and the rest of the log as they were. A report built from logs cut so
// is the one built from the whole logs, and a large sweep's results shrink about tenfold.
void KeepScoresOnly(v1::EvaluationLog& log);

// Each trial of `sweep` with the logs of its completed runs among `runs` (the sweep's, any
// order), in seed order; with `scores_only`, each cut by KeepScoresOnly. Errors as
// CompletedRunLogs::Get.
absl::StatusOr<v1::SweepResults> CollectSweepResults(const SweepRecord& sweep,
                                                     const std::vector<RunRecord>& runs,
                                                     CompletedRunLogs& logs,
                                                     bool scores_only);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SWEEP_RESULTS_H_
