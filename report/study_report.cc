// Copyright 2026 The DCS Authors.
#include "report/study_report.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "common/text_table.h"
#include "coordinator/study_sweep.h"
#include "dcs/proto_json.h"
#include "report/correlation.h"

namespace dcs::report {
namespace {

// "stages[<k>].schedule.family": a stage's mode.
std::string StageModeName(int stage) { return absl::StrCat("stages[", stage, "].schedule.family"); }

// A parameter's value for people: a choice, an integer, a float to 3 significant digits; a
// stage's schedule parameter named "s<k>.<key>".
std::string ParameterText(const run::SearchParameter& parameter, double value) {
  std::string name = parameter.name;
  if (name.starts_with("stages[")) {
    const size_t close = name.find("].schedule.");
    if (close != std::string::npos) {
      name = absl::StrCat("s", name.substr(7, close - 7), ".",
                          name.substr(close + std::string("].schedule.").size()));
    }
  }
  if (const auto* choices = std::get_if<run::CategoricalDistribution>(&parameter.distribution)) {
    return absl::StrCat(name, "=", run::ChoiceOf(*choices, value));
  }
  if (std::holds_alternative<run::IntDistribution>(parameter.distribution)) {
    return absl::StrCat(name, "=", static_cast<int64_t>(value));
  }
  return absl::StrFormat("%s=%.3g", name, value);
}

// Ranks 1..n of `values`, equal values sharing the mean of their ranks (highest value first).
std::vector<double> AverageRanks(const std::vector<double>& values) {
  std::vector<size_t> order(values.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return values[a] > values[b]; });
  std::vector<double> ranks(values.size());
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) ++j;
    for (size_t k = i; k <= j; ++k) ranks[order[k]] = (static_cast<double>(i + j) / 2) + 1;
    i = j + 1;
  }
  return ranks;
}

// Kendall's tau-b of the pairs (x[i], y[i]). nullopt if x or y is constant.
std::optional<double> KendallTauB(const std::vector<double>& x, const std::vector<double>& y) {
  double concordant = 0, discordant = 0, ties_x = 0, ties_y = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    for (size_t j = i + 1; j < x.size(); ++j) {
      const double dx = x[i] - x[j];
      const double dy = y[i] - y[j];
      if (dx == 0 && dy == 0) continue;
      if (dx == 0) {
        ++ties_x;
      } else if (dy == 0) {
        ++ties_y;
      } else {
        (dx * dy > 0 ? concordant : discordant) += 1;
      }
    }
  }
  const double denominator =
      std::sqrt((concordant + discordant + ties_x) * (concordant + discordant + ties_y));
  if (denominator == 0) return std::nullopt;
  return (concordant - discordant) / denominator;
}

// Complete trials first by value (best first; equals by number), then the others by number.
bool RanksBefore(const v1::StudyReport::Trial& a, const v1::StudyReport::Trial& b) {
  if ((a.rank() > 0) != (b.rank() > 0)) return a.rank() > 0;
  if (a.rank() != b.rank()) return a.rank() < b.rank();
  return a.trial() < b.trial();
}

// The ranks of `trials`' values (1 the highest; equals by trial order), set through `rank`.
void SetRanks(std::vector<std::pair<double, v1::StudyReport::Trial*>> valued,
              void (v1::StudyReport::Trial::*set_rank)(int32_t)) {
  std::stable_sort(valued.begin(), valued.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; i < valued.size(); ++i) (valued[i].second->*set_rank)(static_cast<int>(i) + 1);
}

std::string Number(double value) { return absl::StrFormat("%.1f", value); }

}  // namespace

absl::StatusOr<v1::StudyReport> BuildStudyReport(const v1::SweepResults& results,
                                                 const std::vector<coordinator::StudyTrial>& trials,
                                                 int top, const ReportOptions& options) {
  if (results.study_id().empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat(results.sweep_id(), " is not a study sweep: it has no study to report"));
  }
  if (top < 1) return absl::InvalidArgumentError("a study report's top must be at least 1");
  DCS_ASSIGN_OR_RETURN(const coordinator::StudySweepSpec spec,
                       coordinator::ParseStudySweepYaml(results.spec(), results.name()));
  v1::StudyReport report;
  report.set_sweep_id(results.sweep_id());
  report.set_study_id(results.study_id());
  report.set_name(results.name());
  report.set_objective(std::string(NameOf(coordinator::kStudyObjectiveNames, spec.objective)));
  report.set_seeds(static_cast<int>(spec.sweep.seeds.size()));
  report.set_retrain_seeds(static_cast<int>(spec.retrain_seeds.size()));

  // The stages whose mode the space searches.
  int stages = 0;
  while (run::FindParameter(spec.space, StageModeName(stages)) != nullptr) ++stages;
  std::map<int64_t, const v1::TrialResults*> retrained;
  for (const v1::TrialResults& trial : results.trials()) {
    if (trial.retrain() && trial.has_study_trial()) retrained[trial.study_trial()] = &trial;
  }

  std::vector<std::pair<double, v1::StudyReport::Trial*>> complete, retrain_values;
  for (const coordinator::StudyTrial& trial : trials) {
    v1::StudyReport::Trial& row = *report.add_trials();
    row.set_trial(trial.number);
    row.set_state(std::string(NameOf(coordinator::kTrialStateNames, trial.state)));
    if (trial.state == coordinator::TrialState::kComplete) {
      row.set_value(trial.value);
      complete.emplace_back(trial.value, &row);
    } else if (trial.state == coordinator::TrialState::kPruned && !trial.reported.empty()) {
      row.set_value(trial.reported.rbegin()->second);
    }
    for (const run::SearchParameter& parameter : spec.space.parameters) {
      const auto value = trial.values.find(parameter.name);
      if (value == trial.values.end()) continue;
      const auto* choices = std::get_if<run::CategoricalDistribution>(&parameter.distribution);
      bool is_mode = false;
      for (int k = 0; k < stages; ++k) is_mode |= parameter.name == StageModeName(k);
      if (is_mode && choices != nullptr) {
        row.add_stage_modes(run::ChoiceOf(*choices, value->second));
      } else {
        row.add_parameters(ParameterText(parameter, value->second));
      }
    }
    if (auto found = retrained.find(trial.number); found != retrained.end()) {
      const v1::TrialResults& runs = *found->second;
      if (runs.runs_size() == report.retrain_seeds()) {
        const double value = coordinator::TrialObjective(
            spec.objective, std::vector<v1::EvaluationLog>(runs.runs().begin(), runs.runs().end()));
        row.set_retrain_value(value);
        retrain_values.emplace_back(value, &row);
      }
    }
  }
  SetRanks(complete, &v1::StudyReport::Trial::set_rank);
  SetRanks(retrain_values, &v1::StudyReport::Trial::set_retrain_rank);
  std::sort(report.mutable_trials()->pointer_begin(), report.mutable_trials()->pointer_end(),
            [](const v1::StudyReport::Trial* a, const v1::StudyReport::Trial* b) {
              return RanksBefore(*a, *b);
            });

  // The stage modes of the best.
  if (stages > 0) {
    std::vector<std::string> choices;  // every stage's, in order of first appearance
    for (int k = 0; k < stages; ++k) {
      const auto* distribution = std::get_if<run::CategoricalDistribution>(
          &run::FindParameter(spec.space, StageModeName(k))->distribution);
      if (distribution == nullptr) continue;
      for (const std::string& mode : distribution->choices) {
        if (std::find(choices.begin(), choices.end(), mode) == choices.end()) {
          choices.push_back(mode);
        }
      }
    }
    for (const std::string& mode : choices) report.add_modes(mode);
    std::vector<int> counts(static_cast<size_t>(stages) * choices.size(), 0);
    int counted = 0;
    for (const v1::StudyReport::Trial& row : report.trials()) {
      if (row.rank() == 0 || counted == top) break;
      ++counted;
      for (int k = 0; k < row.stage_modes_size(); ++k) {
        const auto mode = std::find(choices.begin(), choices.end(), row.stage_modes(k));
        if (mode != choices.end()) ++counts[k * choices.size() + (mode - choices.begin())];
      }
    }
    report.set_top(counted);
    for (int count : counts) report.add_mode_counts(count);
  }

  // How the ranking held.
  std::vector<double> search, retrain;
  for (const v1::StudyReport::Trial& row : report.trials()) {
    if (row.rank() > 0 && row.has_retrain_value()) {
      search.push_back(row.value());
      retrain.push_back(row.retrain_value());
    }
  }
  report.set_rank_pairs(static_cast<int>(search.size()));
  if (absl::StatusOr<Correlation> rho =
          PearsonCorrelation(AverageRanks(search), AverageRanks(retrain));
      rho.ok()) {
    report.set_spearman_rho(rho->r);
    report.set_spearman_p(rho->p_value);
  }
  if (search.size() >= 3) {
    if (std::optional<double> tau = KendallTauB(search, retrain)) report.set_kendall_tau(*tau);
  }

  // The retrained trials as a sweep, each named by its trial.
  v1::SweepResults retrain_results;
  retrain_results.set_sweep_id(results.sweep_id());
  retrain_results.set_name(absl::StrCat(results.name(), " retrain"));
  retrain_results.set_seeds(report.retrain_seeds());
  for (const auto& [number, trial] : retrained) {
    v1::TrialResults& out = *retrain_results.add_trials();
    out = *trial;
    out.set_condition(coordinator::StudyTrialCondition(number, /*retrain=*/false));
  }
  for (auto [checkpoint, out] :
       {std::pair{ReportCheckpoint::kLast, report.mutable_retrain_last()},
        std::pair{ReportCheckpoint::kBest, report.mutable_retrain_best()}}) {
    ReportOptions table = options;
    table.checkpoint = checkpoint;
    table.split = ReportSplit::kCombined;
    DCS_ASSIGN_OR_RETURN(*out, BuildSweepReport(retrain_results, table));
  }
  return report;
}

std::string FormatStudyReport(const v1::StudyReport& report, ReportFormat format, int rows) {
  const bool markdown = format == ReportFormat::kMarkdown;
  if (format == ReportFormat::kJson) return ProtoToJson(report) + "\n";
  if (format == ReportFormat::kLatex || format == ReportFormat::kHtml) {
    return absl::StrCat(FormatReport(report.retrain_last(), format), "\n",
                        FormatReport(report.retrain_best(), format));
  }
  std::vector<std::vector<std::string>> table = {{"RANK", "TRIAL", "STATE", "OBJECTIVE",
                                                  "STAGE MODES", "PARAMETERS", "RETRAIN",
                                                  "RETRAIN RANK"}};
  for (const v1::StudyReport::Trial& trial : report.trials()) {
    const bool shown = format == ReportFormat::kCsv || trial.has_retrain_value() ||
                       (trial.rank() > 0 && trial.rank() <= rows);
    if (!shown) continue;
    table.push_back({trial.rank() > 0 ? absl::StrCat(trial.rank()) : "",
                     coordinator::StudyTrialCondition(trial.trial(), false), trial.state(),
                     trial.has_value() ? Number(trial.value()) : "",
                     absl::StrJoin(trial.stage_modes(), format == ReportFormat::kCsv ? ";" : " > "),
                     absl::StrJoin(trial.parameters(), format == ReportFormat::kCsv ? ";" : " "),
                     trial.has_retrain_value() ? Number(trial.retrain_value()) : "",
                     trial.retrain_rank() > 0 ? absl::StrCat(trial.retrain_rank()) : ""});
  }
  if (format == ReportFormat::kCsv) {
    std::string csv;
    for (const auto& line : table) absl::StrAppend(&csv, absl::StrJoin(line, ","), "\n");
    return csv;
  }
  auto render = [&](const std::vector<std::vector<std::string>>& lines,
                    const std::vector<bool>& right) {
    if (!markdown) return RenderTable(lines, right);
    std::string out;
    for (size_t i = 0; i < lines.size(); ++i) {
      absl::StrAppend(&out, "| ", absl::StrJoin(lines[i], " | "), " |\n");
      if (i == 0)
        absl::StrAppend(
            &out, "|", absl::StrJoin(std::vector<std::string>(lines[i].size(), "---"), "|"), "|\n");
    }
    return out;
  };
  const std::string heading = markdown ? "### " : "";
  std::string out = absl::StrCat(
      heading, report.name(), " (", report.sweep_id(), ", ", report.study_id(),
      "): trials ranked by ", report.objective(), " over ", report.seeds(), " seeds; the best ",
      rows, " and every retrained one\n\n", render(table, {true, false, false, true}), "\n");
  if (report.top() > 0) {
    std::vector<std::vector<std::string>> modes = {{"STAGE"}};
    for (const std::string& mode : report.modes()) modes[0].push_back(mode);
    const int stages = report.mode_counts_size() / std::max(1, report.modes_size());
    for (int k = 0; k < stages; ++k) {
      std::vector<std::string>& line =
          modes.emplace_back(std::vector<std::string>{absl::StrCat(k + 1)});
      for (int m = 0; m < report.modes_size(); ++m) {
        line.push_back(absl::StrCat(report.mode_counts(k * report.modes_size() + m)));
      }
    }
    absl::StrAppend(&out, heading, "Stage modes of the best ", report.top(), " trials\n\n",
                    render(modes, std::vector<bool>(modes[0].size(), true)), "\n");
  }
  if (report.rank_pairs() > 0) {
    absl::StrAppend(&out, heading, "Retrain: ", report.rank_pairs(), " trials with ",
                    report.retrain_seeds(), " new seeds each\n\n");
    std::vector<std::string> correlations;
    if (report.has_spearman_rho()) {
      correlations.push_back(absl::StrFormat("Spearman rho = %.2f (p = %.2g)",
                                             report.spearman_rho(), report.spearman_p()));
    }
    if (report.has_kendall_tau()) {
      correlations.push_back(absl::StrFormat("Kendall tau-b = %.2f", report.kendall_tau()));
    }
    if (!correlations.empty()) {
      absl::StrAppend(&out, "Search rank vs retrain rank: ", absl::StrJoin(correlations, ", "),
                      "\n\n");
    }
    absl::StrAppend(&out, FormatReport(report.retrain_last(), format), "\n",
                    FormatReport(report.retrain_best(), format));
  }
  return out;
}

}  // namespace dcs::report
