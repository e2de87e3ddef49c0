// Copyright 2026 The DCS Authors.
#include "report/runs_summary.h"

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "run/evaluation_log.h"

namespace dcs::report {
namespace {

constexpr int kBootstrapRepetitions = 10'000;
constexpr uint64_t kBootstrapSeed = 0;

absl::StatusOr<v1::ScoreSummary> SummarizeScore(const std::vector<double>& values) {
  DCS_ASSIGN_OR_RETURN(const coordinator::IqmSummary iqm, coordinator::SummarizeIqm(values));
  DCS_ASSIGN_OR_RETURN(
      const coordinator::ConfidenceInterval interval,
      coordinator::BootstrapIqmInterval({values}, 0.95, kBootstrapRepetitions, kBootstrapSeed));
  v1::ScoreSummary summary;
  summary.set_iqm(iqm.iqm);
  summary.set_q1(iqm.q1);
  summary.set_q3(iqm.q3);
  summary.set_ci_low(interval.lo);
  summary.set_ci_high(interval.hi);
  return summary;
}

}  // namespace

absl::StatusOr<v1::RunScore> ReadRunScore(const std::string& dir) {
  DCS_ASSIGN_OR_RETURN(const v1::EvaluationLog log, run::ReadEvaluationLog(dir));
  if (!log.complete() || log.evaluations_size() == 0) {
    return absl::FailedPreconditionError(absl::StrCat(
        dir, ": the run has not finished (continue it with dcs train --resume --out ", dir, ")"));
  }
  v1::RunScore score;
  score.set_run(dir);
  score.set_seed(log.seed());
  score.set_steps(log.evaluations(log.evaluations_size() - 1).step());
  score.set_last(log.last());
  score.set_best_anytime(log.best_anytime());
  return score;
}

absl::StatusOr<v1::RunsSummary> SummarizeRuns(const std::vector<std::string>& dirs) {
  v1::RunsSummary summary;
  std::vector<double> last;
  std::vector<double> best;
  for (const std::string& dir : dirs) {
    DCS_ASSIGN_OR_RETURN(*summary.add_runs(), ReadRunScore(dir));
    last.push_back(summary.runs().rbegin()->last());
    best.push_back(summary.runs().rbegin()->best_anytime());
  }
  DCS_ASSIGN_OR_RETURN(*summary.mutable_last(), SummarizeScore(last));
  DCS_ASSIGN_OR_RETURN(*summary.mutable_best_anytime(), SummarizeScore(best));
  return summary;
}

}  // namespace dcs::report
