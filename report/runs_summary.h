// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_RUNS_SUMMARY_H_
#define DCS_REPORT_RUNS_SUMMARY_H_

// One row of the paper's tables from finished runs of one condition (`dcs summarize`): each
// run's two scores, last and best-anytime avg_combined (docs/reference.md, "Scores"), read from its
// evaluation log (run/evaluation_log.h), and across the runs IQM [Q1, Q3] with a 95%
// stratified-bootstrap interval (coordinator/iqm.h; 10,000 resamples from seed 0, so the same
// runs give the same interval). Thread-safe (pure functions over files).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "dcs/v1/evaluation.pb.h"

namespace dcs::report {

// The scores of the finished run in `dir`. NOT_FOUND without an evaluation log, DATA_LOSS for
// an unreadable one, FAILED_PRECONDITION for a run that has not finished.
absl::StatusOr<v1::RunScore> ReadRunScore(const std::string& dir);

// Every run's scores and both scores across them. Errors as ReadRunScore, naming the run.
absl::StatusOr<v1::RunsSummary> SummarizeRuns(const std::vector<std::string>& dirs);

}  // namespace dcs::report

#endif  // DCS_REPORT_RUNS_SUMMARY_H_
