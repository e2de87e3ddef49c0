// Copyright 2026 The DCS Authors.
#ifndef DCS_REPORT_SWEEP_REPORT_H_
#define DCS_REPORT_SWEEP_REPORT_H_

// A sweep's report (dcs/v1/report.proto): the paper's tables (docs/reference.md, "Scores",
// Appendix F) from a sweep's finished runs. Each run gives one score, read at one checkpoint
// (last or best) and one split (avg_combined or a split's mean); per condition and observation
// mode, IQM [Q1, Q3] of the scores across seeds, a bootstrap interval of the IQM over seeds
// (coordinator/iqm.h) and rliable's probability of improvement over the static baseline
// (report/probability_of_improvement.h), tested for a difference with Mann-Whitney's test,
// Holm-adjusted over the mode's conditions (report/significance.h); and if runs counted
// coverage, the coverage diagnostic (report/coverage_report.h). Thread-safe (pure
// functions).

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/split.h"
#include "common/enum_names.h"
#include "dcs/v1/report.pb.h"
#include "dcs/v1/sweep.pb.h"

namespace dcs::report {

// Which evaluation of a run is read: the final one (the paper's primary result), or the one
// with the highest avg_combined (best-anytime; multi-stage runs: among stage boundaries and the
// end, as EvaluationLog.best_anytime_index records it).
enum class ReportCheckpoint { kLast, kBest };
inline constexpr EnumName<ReportCheckpoint> kReportCheckpointNames[] = {
    {ReportCheckpoint::kLast, "last"}, {ReportCheckpoint::kBest, "best"}};
static_assert(InEnumOrder(kReportCheckpointNames));

// Which value of that evaluation is the score: avg_combined, or one split's mean. The splits'
// names are actor::kSplitNames'.
enum class ReportSplit { kCombined, kId, kOodLow, kOodHigh };
inline constexpr EnumName<ReportSplit> kReportSplitNames[] = {
    {ReportSplit::kCombined, "combined"},
    {ReportSplit::kId, NameOf(actor::kSplitNames, actor::Split::kId)},
    {ReportSplit::kOodLow, NameOf(actor::kSplitNames, actor::Split::kOodLow)},
    {ReportSplit::kOodHigh, NameOf(actor::kSplitNames, actor::Split::kOodHigh)}};
static_assert(InEnumOrder(kReportSplitNames));

struct ReportOptions {
  ReportCheckpoint checkpoint = ReportCheckpoint::kLast;
  ReportSplit split = ReportSplit::kCombined;
  int bootstrap_resamples = 10'000;
  uint64_t bootstrap_seed = 0;
  double confidence = 0.95;
  // The condition the probabilities of improvement compare with. Empty: the first condition
  // whose family is "static", or none if the sweep has none (then no cell has an improvement).
  std::string baseline;
};

// The report of `results`. Rows: conditions in the sweep's order, the baseline moved first;
// columns: observation modes in the order they first appear. Every condition has a cell in
// every mode, marked empty while it has no finished run (or the sweep has no such trial). The
// interval of a cell's IQM resamples its runs from StreamSeed(bootstrap_seed, "bootstrap"), the
// same stream for every cell (so a cell's interval depends only on its scores and the options,
// and equals `dcs summarize`'s for the same scores); the improvement's from
// StreamSeed(bootstrap_seed, "improvement"). The same input gives the same report bit for bit.
// INVALID_ARGUMENT for bad options (resamples < 1, confidence outside (0, 1)), a baseline named
// that is not a condition, a trial without a condition or mode name, a condition given two
// families, a condition in one mode twice, a seed twice in a trial, and for a run (named by its
// trial and seed) that is not complete, has no evaluations, lacks the split asked for, whose
// best_anytime_index is out of range or disagrees with best_anytime, or whose score is NaN or
// infinite.
absl::StatusOr<v1::SweepReport> BuildSweepReport(const v1::SweepResults& results,
                                                 const ReportOptions& options);

}  // namespace dcs::report

#endif  // DCS_REPORT_SWEEP_REPORT_H_
