// Copyright 2026 The DCS Authors.
#include "report/coverage_report.h"

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"
#include "report/anova.h"
#include "report/correlation.h"
#include "report/sample_stats.h"

namespace dcs::report {
namespace {

const v1::ProjectionCoverage* FindProjection(const v1::EvaluationLog& log,
                                             const std::string& projection) {
  for (const v1::ProjectionCoverage& coverage : log.coverage()) {
    if (coverage.projection() == projection) return &coverage;
  }
  return nullptr;
}

// Each projection any run counted, in order of first appearance, with its cells and the longest
// list of windows. INVALID_ARGUMENT for a projection whose cells differ between runs.
absl::StatusOr<std::vector<v1::CoverageSection>> Sections(const v1::SweepResults& results) {
  std::vector<v1::CoverageSection> sections;
  absl::flat_hash_map<std::string, size_t> index;
  for (const v1::TrialResults& trial : results.trials()) {
    for (const v1::EvaluationLog& log : trial.runs()) {
      for (const v1::ProjectionCoverage& coverage : log.coverage()) {
        const auto [it, added] = index.try_emplace(coverage.projection(), sections.size());
        if (added) {
          sections.emplace_back().set_projection(coverage.projection());
          sections.back().set_cells(coverage.cells());
        }
        v1::CoverageSection& section = sections[it->second];
        if (section.cells() != coverage.cells()) {
          return absl::InvalidArgumentError(absl::StrCat(
              "trial ", trial.condition(), " (", trial.observe(), "), seed ", log.seed(),
              ": projection ", coverage.projection(), " has ", coverage.cells(),
              " cells, other runs' ", section.cells()));
        }
        if (coverage.windows_size() > section.window_ends_size()) {
          section.clear_window_starts();
          section.clear_window_ends();
          for (const v1::CoverageWindow& window : coverage.windows()) {
            section.add_window_starts(window.start_step());
            section.add_window_ends(window.end_step());
          }
        }
      }
    }
  }
  return sections;
}

double Percent(int64_t cells, int64_t of) {
  return 100.0 * static_cast<double>(cells) / static_cast<double>(of);
}

// Runs' report scores and their coverage, pair by pair (for the correlation of the two).
struct ScoredCoverage {
  std::vector<double> scores;
  std::vector<double> coverage;
};

// The row of `trial`'s runs in `section`, whose report scores `cell` holds in order. Adds each
// run's score and coverage to `scored`. Rows without runs have none.
v1::CoverageRow RowOf(const v1::TrialResults& trial, const v1::ReportCell& cell,
                      const v1::CoverageSection& section, ScoredCoverage& scored) {
  v1::CoverageRow row;
  row.set_condition(trial.condition());
  row.set_mode(trial.observe());
  std::vector<double> window_sums(section.window_ends_size());
  std::vector<int> window_runs(section.window_ends_size());
  for (int i = 0; i < trial.runs_size(); ++i) {
    const v1::ProjectionCoverage* coverage = FindProjection(trial.runs(i), section.projection());
    if (coverage == nullptr) continue;
    int64_t visited = 0;
    for (int w = 0; w < coverage->windows_size(); ++w) {
      visited += coverage->windows(w).new_cells();
      window_sums[w] += Percent(coverage->windows(w).visited(), section.cells());
      ++window_runs[w];
    }
    row.add_runs(Percent(visited, section.cells()));
    scored.scores.push_back(cell.scores(i).score());
    scored.coverage.push_back(row.runs(row.runs_size() - 1));
  }
  if (row.runs().empty()) return row;
  const std::span<const double> runs(row.runs().data(), row.runs().size());
  row.set_mean(Mean(runs));
  row.set_sem(StandardError(runs));
  for (size_t w = 0; w < window_sums.size(); ++w) {
    row.add_window_means(window_runs[w] > 0 ? window_sums[w] / window_runs[w] : 0);
  }
  return row;
}

// The tests of one mode over its rows and its runs' scores and coverage.
v1::CoverageTest TestOf(const std::string& mode, const std::vector<v1::CoverageRow>& rows,
                        const ScoredCoverage& scored) {
  v1::CoverageTest test;
  test.set_mode(mode);
  std::vector<std::string> notes;
  std::vector<std::vector<double>> groups;
  for (const v1::CoverageRow& row : rows) groups.emplace_back(row.runs().begin(), row.runs().end());
  if (absl::StatusOr<AnovaResult> anova = OneWayAnova(groups); anova.ok()) {
    test.mutable_anova()->set_f(anova->f);
    test.mutable_anova()->set_df_between(anova->df_between);
    test.mutable_anova()->set_df_within(anova->df_within);
    test.mutable_anova()->set_p_value(anova->p_value);
  } else {
    notes.push_back(absl::StrCat("no ANOVA: ", anova.status().message()));
  }
  if (absl::StatusOr<Correlation> r = PearsonCorrelation(scored.scores, scored.coverage);
      r.ok()) {
    test.mutable_correlation()->set_r(r->r);
    test.mutable_correlation()->set_p_value(r->p_value);
    test.mutable_correlation()->set_runs(r->n);
  } else {
    notes.push_back(absl::StrCat("no correlation: ", r.status().message()));
  }
  test.set_note(absl::StrJoin(notes, "; "));
  return test;
}

}  // namespace

absl::Status AddCoverageSections(const v1::SweepResults& results, v1::SweepReport& report) {
  DCS_ASSIGN_OR_RETURN(std::vector<v1::CoverageSection> sections, Sections(results));
  absl::flat_hash_map<std::pair<std::string, std::string>, const v1::TrialResults*> trials;
  for (const v1::TrialResults& trial : results.trials()) {
    trials[{trial.condition(), trial.observe()}] = &trial;
  }
  for (v1::CoverageSection& section : sections) {
    for (int m = 0; m < report.modes_size(); ++m) {
      std::vector<v1::CoverageRow> rows;
      ScoredCoverage scored;
      for (const v1::ReportRow& report_row : report.rows()) {
        const auto trial = trials.find({report_row.condition(), report.modes(m)});
        if (trial == trials.end()) continue;
        v1::CoverageRow row = RowOf(*trial->second, report_row.cells(m), section, scored);
        if (row.runs_size() > 0) rows.push_back(std::move(row));
      }
      if (rows.empty()) continue;
      *section.add_tests() = TestOf(report.modes(m), rows, scored);
      for (v1::CoverageRow& row : rows) *section.add_rows() = std::move(row);
    }
    *report.add_coverage() = std::move(section);
  }
  return absl::OkStatus();
}

}  // namespace dcs::report
