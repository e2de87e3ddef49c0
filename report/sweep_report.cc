// Copyright 2026 The DCS Authors.
#include "report/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "report/coverage_report.h"
#include "report/probability_of_improvement.h"
#include "report/significance.h"

namespace dcs::report {
namespace {

// The family of a condition without a schedule (dcs/v1/sweep.proto).
constexpr absl::string_view kStaticFamily = "static";

constexpr absl::string_view kIqmRule =
    "IQM = the 25% trimmed mean of the runs' scores (floor(n/4) dropped at each end; rliable, "
    "scipy.stats.trim_mean(x, 0.25))";
constexpr absl::string_view kQuartileRule =
    "Q1, Q3 = the 25th and 75th percentiles, linear interpolation between order statistics "
    "(numpy's default)";
constexpr absl::string_view kIntervalRule =
    "percentile bootstrap of the IQM, resampling runs (seeds) with replacement, never episodes";
constexpr absl::string_view kImprovementRule =
    "P(X > Y) + 0.5 P(X = Y) over all pairs of a run X of the condition and a run Y of the "
    "baseline in the same mode (rliable), with a percentile bootstrap resampling both sides' "
    "runs independently";
constexpr absl::string_view kSignificanceRule =
    "two-sided Mann-Whitney U test of the condition's runs against the baseline's (normal "
    "approximation with tie and continuity corrections, scipy.stats.mannwhitneyu's asymptotic "
    "method), its p-value adjusted by Holm's step-down over the mode's comparisons with the "
    "baseline; significant when the adjusted p-value is below 1 - confidence";

// A condition of the sweep: its trials by mode.
struct Condition {
  std::string name;
  std::string family;
  absl::flat_hash_map<std::string, const v1::TrialResults*> trials;  // by mode
};

struct Layout {
  std::vector<std::string> modes;     // in order of first appearance
  std::vector<Condition> conditions;  // in order of first appearance
};

absl::Status CheckOptions(const ReportOptions& options) {
  if (options.bootstrap_resamples < 1) {
    return absl::InvalidArgumentError(absl::StrCat(
        "bootstrap resamples must be at least 1, got ", options.bootstrap_resamples));
  }
  if (!(options.confidence > 0 && options.confidence < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("confidence must be in (0, 1), got ", options.confidence));
  }
  return absl::OkStatus();
}

std::string TrialName(const v1::TrialResults& trial) {
  return absl::StrCat("trial ", trial.condition(), " (", trial.observe(), ")");
}

absl::StatusOr<Layout> LayOut(const v1::SweepResults& results) {
  Layout layout;
  absl::flat_hash_map<std::string, size_t> condition_index;
  std::set<std::string> modes;
  for (const v1::TrialResults& trial : results.trials()) {
    if (trial.condition().empty() || trial.observe().empty()) {
      return absl::InvalidArgumentError(
          absl::StrCat(TrialName(trial), ": a trial needs a condition and an observation mode"));
    }
    if (modes.insert(trial.observe()).second) layout.modes.push_back(trial.observe());
    const auto [it, added] = condition_index.try_emplace(trial.condition(),
                                                         layout.conditions.size());
    if (added) layout.conditions.push_back({.name = trial.condition(), .family = trial.family()});
    Condition& condition = layout.conditions[it->second];
    if (condition.family != trial.family()) {
      return absl::InvalidArgumentError(
          absl::StrCat(TrialName(trial), ": family ", trial.family(), ", but the condition's ",
                       "other trials have family ", condition.family));
    }
    if (!condition.trials.try_emplace(trial.observe(), &trial).second) {
      return absl::InvalidArgumentError(
          absl::StrCat(TrialName(trial), ": the sweep holds this trial twice"));
    }
  }
  return layout;
}

// The index of the baseline condition in `layout`, or -1 if the sweep has none.
absl::StatusOr<int> FindBaseline(const Layout& layout, const std::string& name) {
  for (size_t i = 0; i < layout.conditions.size(); ++i) {
    const Condition& condition = layout.conditions[i];
    if (name.empty() ? condition.family == kStaticFamily : condition.name == name) {
      return static_cast<int>(i);
    }
  }
  if (name.empty()) return -1;
  std::string known;
  for (const Condition& condition : layout.conditions) {
    absl::StrAppend(&known, known.empty() ? "" : ", ", condition.name);
  }
  return absl::InvalidArgumentError(absl::StrCat("the baseline ", name,
                                                 " is not a condition of the sweep (",
                                                 known.empty() ? "none" : known, ")"));
}

// The evaluation of `log` that `checkpoint` reads. Errors without context (the caller adds it).
absl::StatusOr<const v1::Evaluation*> CheckpointEvaluation(const v1::EvaluationLog& log,
                                                           ReportCheckpoint checkpoint) {
  if (!log.complete()) return absl::InvalidArgumentError("the run has not finished");
  if (log.evaluations().empty()) return absl::InvalidArgumentError("the run has no evaluations");
  switch (checkpoint) {
    case ReportCheckpoint::kLast:
      return &log.evaluations(log.evaluations_size() - 1);
    case ReportCheckpoint::kBest: {
      const int index = log.best_anytime_index();
      if (index < 0 || index >= log.evaluations_size()) {
        return absl::InvalidArgumentError(absl::StrCat("best_anytime_index ", index,
                                                       " is not one of its ",
                                                       log.evaluations_size(), " evaluations"));
      }
      const v1::Evaluation& best = log.evaluations(index);
      if (best.avg_combined() != log.best_anytime()) {
        return absl::InvalidArgumentError(absl::StrCat(
            "best_anytime ", log.best_anytime(), " is not the avg_combined of evaluation ", index,
            " (", best.avg_combined(), ")"));
      }
      return &best;
    }
  }
  return absl::InternalError("unknown checkpoint");
}

// The score `split` reads from `evaluation`. Errors without context.
absl::StatusOr<double> SplitValue(const v1::Evaluation& evaluation, ReportSplit split) {
  if (split == ReportSplit::kCombined) return evaluation.avg_combined();
  const bool present = split == ReportSplit::kId      ? evaluation.has_id()
                       : split == ReportSplit::kOodLow ? evaluation.has_ood_low()
                                                       : evaluation.has_ood_high();
  if (!present) {
    return absl::InvalidArgumentError(absl::StrCat("the evaluation at step ", evaluation.step(),
                                                   " has no ", NameOf(kReportSplitNames, split),
                                                   " split"));
  }
  return split == ReportSplit::kId       ? evaluation.id().mean()
         : split == ReportSplit::kOodLow ? evaluation.ood_low().mean()
                                         : evaluation.ood_high().mean();
}

absl::StatusOr<v1::ReportRun> ReadRun(const v1::TrialResults& trial, const v1::EvaluationLog& log,
                                      const ReportOptions& options) {
  const auto in_context = [&](const absl::Status& status) {
    return absl::InvalidArgumentError(
        absl::StrCat(TrialName(trial), ", seed ", log.seed(), ": ", status.message()));
  };
  absl::StatusOr<const v1::Evaluation*> evaluation = CheckpointEvaluation(log, options.checkpoint);
  if (!evaluation.ok()) return in_context(evaluation.status());
  absl::StatusOr<double> score = SplitValue(**evaluation, options.split);
  if (!score.ok()) return in_context(score.status());
  if (!std::isfinite(*score)) {
    return in_context(absl::InvalidArgumentError(absl::StrCat(
        "the score (", NameOf(kReportSplitNames, options.split), " at the ",
        NameOf(kReportCheckpointNames, options.checkpoint), " checkpoint, step ",
        (*evaluation)->step(), ") is ", *score)));
  }
  v1::ReportRun run;
  run.set_seed(log.seed());
  run.set_score(*score);
  run.set_step((*evaluation)->step());
  return run;
}

// The cell of `trial` (null: the sweep has no such trial) in `mode`, without improvement and
// best.
absl::StatusOr<v1::ReportCell> BuildCell(const v1::TrialResults* trial, const std::string& mode,
                                         int seeds, const ReportOptions& options) {
  v1::ReportCell cell;
  cell.set_mode(mode);
  cell.set_seeds(trial == nullptr ? 0 : seeds);
  cell.set_empty(true);
  if (trial == nullptr || trial->runs().empty()) return cell;
  std::vector<double> scores;
  std::set<uint64_t> seen;
  for (const v1::EvaluationLog& log : trial->runs()) {
    if (!seen.insert(log.seed()).second) {
      return absl::InvalidArgumentError(
          absl::StrCat(TrialName(*trial), ", seed ", log.seed(), ": the seed has two runs"));
    }
    DCS_ASSIGN_OR_RETURN(*cell.add_scores(), ReadRun(*trial, log, options));
    scores.push_back(cell.scores().rbegin()->score());
  }
  DCS_ASSIGN_OR_RETURN(const coordinator::IqmSummary iqm, coordinator::SummarizeIqm(scores));
  DCS_ASSIGN_OR_RETURN(
      const coordinator::ConfidenceInterval interval,
      coordinator::BootstrapIqmInterval({scores}, options.confidence, options.bootstrap_resamples,
                                        options.bootstrap_seed));
  cell.set_runs(static_cast<int>(scores.size()));
  cell.set_empty(false);
  v1::ScoreSummary* summary = cell.mutable_summary();
  summary->set_iqm(iqm.iqm);
  summary->set_q1(iqm.q1);
  summary->set_q3(iqm.q3);
  summary->set_ci_low(interval.lo);
  summary->set_ci_high(interval.hi);
  return cell;
}

std::vector<double> Scores(const v1::ReportCell& cell) {
  std::vector<double> scores;
  for (const v1::ReportRun& run : cell.scores()) scores.push_back(run.score());
  return scores;
}

// Sets each cell's improvement over the baseline's cell of its mode (the baseline is row 0),
// its test, and per mode the Holm adjustment over the mode's cells compared.
absl::Status AddImprovements(const ReportOptions& options, v1::SweepReport& report) {
  const v1::ReportRow& baseline = report.rows(0);
  for (int m = 0; m < report.modes_size(); ++m) {
    std::vector<v1::Improvement*> compared;
    std::vector<double> p_values;
    for (int r = 1; r < report.rows_size(); ++r) {
      v1::ReportCell& cell = *report.mutable_rows(r)->mutable_cells(m);
      if (cell.empty() || baseline.cells(m).empty()) continue;
      const std::vector<double> x = Scores(cell);
      const std::vector<double> y = Scores(baseline.cells(m));
      DCS_ASSIGN_OR_RETURN(const double probability, ProbabilityOfImprovement(x, y));
      DCS_ASSIGN_OR_RETURN(
          const coordinator::ConfidenceInterval interval,
          BootstrapImprovementInterval(x, y, options.confidence, options.bootstrap_resamples,
                                       options.bootstrap_seed));
      DCS_ASSIGN_OR_RETURN(const MannWhitney test, MannWhitneyTest(x, y));
      v1::Improvement& improvement = *cell.mutable_improvement();
      improvement.set_probability(probability);
      improvement.set_ci_low(interval.lo);
      improvement.set_ci_high(interval.hi);
      improvement.set_p_value(test.p_value);
      compared.push_back(&improvement);
      p_values.push_back(test.p_value);
    }
    DCS_ASSIGN_OR_RETURN(const std::vector<double> adjusted, HolmAdjusted(p_values));
    for (size_t i = 0; i < compared.size(); ++i) {
      compared[i]->set_holm_p_value(adjusted[i]);
      compared[i]->set_significant(adjusted[i] < 1 - options.confidence);
    }
  }
  return absl::OkStatus();
}

// Flags, in each mode, every non-empty cell whose IQM is the highest.
void MarkBest(v1::SweepReport& report) {
  for (int m = 0; m < report.modes_size(); ++m) {
    bool any = false;
    double best = 0;
    for (const v1::ReportRow& row : report.rows()) {
      const v1::ReportCell& cell = row.cells(m);
      if (cell.empty()) continue;
      best = any ? std::max(best, cell.summary().iqm()) : cell.summary().iqm();
      any = true;
    }
    for (v1::ReportRow& row : *report.mutable_rows()) {
      v1::ReportCell& cell = *row.mutable_cells(m);
      cell.set_best(any && !cell.empty() && cell.summary().iqm() == best);
    }
  }
}

std::string ScoreRule(const ReportOptions& options) {
  const std::string value =
      options.split == ReportSplit::kCombined
          ? "avg_combined"
          : absl::StrCat("the ", NameOf(kReportSplitNames, options.split), " split's mean");
  if (options.checkpoint == ReportCheckpoint::kLast) {
    return absl::StrCat(value, " at the final evaluation (last checkpoint)");
  }
  return absl::StrCat(value,
                      " at the evaluation with the highest avg_combined (best checkpoint",
                      options.split == ReportSplit::kCombined ? "" : ", chosen by avg_combined",
                      "; multi-stage runs: among stage boundaries and the end)");
}

v1::ReportSettings Settings(const ReportOptions& options, const std::string& baseline) {
  v1::ReportSettings settings;
  settings.set_checkpoint(std::string(NameOf(kReportCheckpointNames, options.checkpoint)));
  settings.set_split(std::string(NameOf(kReportSplitNames, options.split)));
  settings.set_score_rule(ScoreRule(options));
  settings.set_bootstrap_resamples(options.bootstrap_resamples);
  settings.set_bootstrap_seed(options.bootstrap_seed);
  settings.set_confidence(options.confidence);
  settings.set_iqm_rule(std::string(kIqmRule));
  settings.set_quartile_rule(std::string(kQuartileRule));
  settings.set_interval_rule(std::string(kIntervalRule));
  settings.set_improvement_rule(std::string(kImprovementRule));
  settings.set_significance_rule(std::string(kSignificanceRule));
  settings.set_baseline(baseline);
  return settings;
}

}  // namespace

absl::StatusOr<v1::SweepReport> BuildSweepReport(const v1::SweepResults& results,
                                                 const ReportOptions& options) {
  DCS_RETURN_IF_ERROR(CheckOptions(options));
  DCS_ASSIGN_OR_RETURN(const Layout layout, LayOut(results));
  DCS_ASSIGN_OR_RETURN(const int baseline, FindBaseline(layout, options.baseline));
  v1::SweepReport report;
  report.set_sweep_id(results.sweep_id());
  report.set_name(results.name());
  report.set_seeds(results.seeds());
  *report.mutable_settings() =
      Settings(options, baseline < 0 ? "" : layout.conditions[baseline].name);
  for (const std::string& mode : layout.modes) report.add_modes(mode);
  // The baseline first, then the others in the sweep's order.
  std::vector<int> order;
  if (baseline >= 0) order.push_back(baseline);
  for (int i = 0; i < static_cast<int>(layout.conditions.size()); ++i) {
    if (i != baseline) order.push_back(i);
  }
  for (const int i : order) {
    const Condition& condition = layout.conditions[i];
    v1::ReportRow& row = *report.add_rows();
    row.set_condition(condition.name);
    row.set_family(condition.family);
    row.set_baseline(i == baseline);
    for (const std::string& mode : layout.modes) {
      const auto trial = condition.trials.find(mode);
      DCS_ASSIGN_OR_RETURN(
          *row.add_cells(),
          BuildCell(trial == condition.trials.end() ? nullptr : trial->second, mode,
                    results.seeds(), options));
    }
  }
  if (baseline >= 0) DCS_RETURN_IF_ERROR(AddImprovements(options, report));
  MarkBest(report);
  DCS_RETURN_IF_ERROR(AddCoverageSections(results, report));
  return report;
}

}  // namespace dcs::report
