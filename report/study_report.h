// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_STUDY_REPORT_H_
#define DCS_REPORT_STUDY_REPORT_H_

// A study sweep's report (dcs/v1/report.proto StudyReport), as the paper reports its multi-stage
// search (docs/reference.md, "Multi-stage schedules"; the paper's Table 3, Appendix E): the trials
// ranked by the search's objective; the stage modes the best trials chose (the paper's heatmap);
// and, once the best were retrained with new seeds, how the ranking held (the paper's rank-shift
// figure: search rank against retrain rank, with Spearman's and Kendall's rank correlations) and
// their scores as the paper's Table 3 (IQM [Q1, Q3] with bootstrap intervals of the last and the
// best-anytime avg_combined). Thread-safe (pure functions).

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/sampler.h"
#include "coordinator/study_sweep_spec.h"
#include "dcs/v1/report.pb.h"
#include "dcs/v1/sweep.pb.h"
#include "report/report_format.h"
#include "report/sweep_report.h"

namespace dcs::report {

// The report of the study sweep whose results are `results` (its spec, its trials' logs) and
// whose study's trials are `trials`. `top`: how many of the best complete trials the stage-mode
// counts cover; `options` (checkpoint and split aside) the retrain tables'. INVALID_ARGUMENT for
// results of a plain sweep, a spec that does not parse, top < 1, or options BuildSweepReport
// refuses.
absl::StatusOr<v1::StudyReport> BuildStudyReport(const v1::SweepResults& results,
                                                 const std::vector<coordinator::StudyTrial>& trials,
                                                 int top, const ReportOptions& options);

// `report` as `format`, ending with a newline. table and md: the ranking (the best `rows`
// complete trials, and every retrained one), the stage-mode counts and the rank correlations,
// then the retrain tables as FormatReport writes them; csv: a row per trial; json: the
// StudyReport in protobuf's JSON mapping; latex and html: the retrain tables only (what a paper
// or a page shows).
std::string FormatStudyReport(const v1::StudyReport& report, ReportFormat format, int rows);

}  // namespace dcs::report

#endif  // DCS_REPORT_STUDY_REPORT_H_
