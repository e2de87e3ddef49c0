// Copyright 2026 The DCS Authors.
#include "coordinator/study_table.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Statement.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/store_connection.h"
#include "coordinator/store_rows.h"
#include "run/search_space_yaml.h"

namespace dcs::coordinator {
namespace {

using namespace store_rows;  // NOLINT: the store's own rows

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

absl::StatusOr<std::vector<StudyTrial>> ReadTrials(SQLite::Database& db, int64_t study) {
  std::vector<StudyTrial> trials;
  std::map<int64_t, size_t> index;
  SQLite::Statement rows(
      db, "SELECT number, state, value FROM study_trials WHERE study = ? ORDER BY number");
  rows.bind(1, study);
  while (rows.executeStep()) {
    const int64_t number = rows.getColumn(0).getInt64();
    DCS_ASSIGN_OR_RETURN(
        const TrialState state,
        StoredValue(db, kTrialStateNames, rows.getColumn(1).getString(),
                    absl::StrCat("the state of trial ", number, " of ", StudyId(study))));
    index[number] = trials.size();
    trials.push_back({.number = number, .state = state, .value = DoubleOrNaN(rows.getColumn(2))});
  }
  // A value or report of a trial the study lacks: the foreign keys forbid it, so the file was
  // damaged.
  auto trial_of = [&](int64_t number) -> absl::StatusOr<StudyTrial*> {
    const auto found = index.find(number);
    if (found == index.end()) {
      return CorruptStore(db.getFilename(), absl::StrCat(StudyId(study), " has values of trial ",
                                                         number, ", which it does not have"));
    }
    return &trials[found->second];
  };
  SQLite::Statement values(db, "SELECT trial, name, value FROM study_trial_values WHERE study = ?");
  values.bind(1, study);
  while (values.executeStep()) {
    DCS_ASSIGN_OR_RETURN(StudyTrial* const trial, trial_of(values.getColumn(0).getInt64()));
    trial->values[values.getColumn(1).getString()] = values.getColumn(2).getDouble();
  }
  SQLite::Statement reports(db,
                            "SELECT trial, step, value FROM study_trial_reports WHERE study = ?");
  reports.bind(1, study);
  while (reports.executeStep()) {
    DCS_ASSIGN_OR_RETURN(StudyTrial* const trial, trial_of(reports.getColumn(0).getInt64()));
    trial->reported[reports.getColumn(1).getInt64()] = DoubleOrNaN(reports.getColumn(2));
  }
  return trials;
}

// A study as the store holds it: its record, its space parsed, its row number and its trials
// (read once per call).
struct StudyRow {
  StudyRecord record;
  run::SearchSpace space;
  int64_t number = 0;
  std::vector<StudyTrial> trials;  // by number
};

absl::StatusOr<StudyRow> FindStudy(SQLite::Database& db, absl::string_view study_id) {
  DCS_ASSIGN_OR_RETURN(const int64_t number, StudyNumber(study_id));
  SQLite::Statement query(db,
                          "SELECT request_id, name, space, sampler, seed, direction, "
                          "startup_trials, ei_candidates, multivariate, grouped, constant_liar, "
                          "created_at, pruner, median_percentile, median_startup_trials, "
                          "median_warmup_steps, median_interval_steps, median_min_trials, "
                          "halving_min_resource, halving_reduction_factor, "
                          "halving_min_early_stopping_rate, halving_bootstrap_count, sweep "
                          "FROM studies WHERE number = ?");
  query.bind(1, number);
  if (!query.executeStep()) return absl::NotFoundError(absl::StrCat("no study ", study_id));
  StudyRow row;
  StudySubmission& s = row.record.submission;
  s.request_id = query.getColumn(0).getString();
  s.name = query.getColumn(1).getString();
  s.space = query.getColumn(2).getString();
  row.record.id = StudyId(number);
  DCS_ASSIGN_OR_RETURN(s.sampler, StoredValue(db, kSamplerKindNames, query.getColumn(3).getString(),
                                              absl::StrCat("the sampler of ", row.record.id)));
  s.seed = static_cast<uint64_t>(query.getColumn(4).getInt64());
  DCS_ASSIGN_OR_RETURN(s.direction, StoredValue(db, kDirectionNames, query.getColumn(5).getString(),
                                                absl::StrCat("the direction of ", row.record.id)));
  s.tpe.startup_trials = query.getColumn(6).getInt();
  s.tpe.ei_candidates = query.getColumn(7).getInt();
  s.tpe.parzen.multivariate = query.getColumn(8).getInt() != 0;
  s.tpe.group = query.getColumn(9).getInt() != 0;
  s.tpe.constant_liar = query.getColumn(10).getInt() != 0;
  row.record.created_at = FromMicros(query.getColumn(11).getInt64());
  PrunerOptions& pruner = s.pruner;
  DCS_ASSIGN_OR_RETURN(pruner.kind,
                       StoredValue(db, kPrunerKindNames, query.getColumn(12).getString(),
                                   absl::StrCat("the pruner of ", row.record.id)));
  pruner.median = {.percentile = query.getColumn(13).getDouble(),
                   .startup_trials = query.getColumn(14).getInt(),
                   .warmup_steps = query.getColumn(15).getInt64(),
                   .interval_steps = query.getColumn(16).getInt64(),
                   .min_trials = query.getColumn(17).getInt()};
  if (!query.getColumn(18).isNull()) pruner.halving.min_resource = query.getColumn(18).getInt64();
  pruner.halving.reduction_factor = query.getColumn(19).getInt();
  pruner.halving.min_early_stopping_rate = query.getColumn(20).getInt();
  pruner.halving.bootstrap_count = query.getColumn(21).getInt();
  if (!query.getColumn(22).isNull()) row.record.sweep_id = SweepId(query.getColumn(22).getInt64());
  // Validated when the study was created: one that no longer parses was damaged since.
  absl::StatusOr<run::SearchSpace> space = run::ParseSearchSpaceYaml(s.space, row.record.id);
  if (!space.ok()) {
    return CorruptStore(db.getFilename(), absl::StrCat("the search space of ", row.record.id,
                                                       " does not parse: ",
                                                       space.status().message()));
  }
  row.space = *std::move(space);

  row.number = number;
  DCS_ASSIGN_OR_RETURN(row.trials, ReadTrials(db, number));
  const std::vector<StudyTrial>& trials = row.trials;
  for (const EnumName<TrialState>& entry : kTrialStateNames) {
    // Not a structured binding: lambdas may capture those since C++20, clang only from 16.
    const TrialState state = entry.value;
    row.record.trials_by_state.emplace_back(
        state, std::count_if(trials.begin(), trials.end(),
                             [state](const StudyTrial& t) { return t.state == state; }));
  }
  for (const StudyTrial& trial : trials) {
    if (trial.state == TrialState::kComplete &&
        (!row.record.best.has_value() ||
         IsBetter(s.direction, trial.value, row.record.best->value))) {
      row.record.best = trial;
    }
  }
  return row;
}

std::unique_ptr<Sampler> MakeSampler(const StudySubmission& study) {
  switch (study.sampler) {
    case SamplerKind::kTpe:
      return MakeTpeSampler(study.seed, study.direction, study.tpe);
    case SamplerKind::kRandom:
      return MakeRandomSampler(study.seed);
  }
  return nullptr;
}

// The study's trial `number`. NOT_FOUND naming both.
absl::StatusOr<StudyTrial*> FindTrial(StudyRow& row, int64_t number) {
  for (StudyTrial& trial : row.trials) {
    if (trial.number == number) return &trial;
  }
  return absl::NotFoundError(absl::StrCat("study ", row.record.id, " has no trial ", number));
}

absl::Status RequireRunning(TrialState state, absl::string_view study_id, int64_t number) {
  if (state == TrialState::kRunning) return absl::OkStatus();
  return absl::FailedPreconditionError(absl::StrCat("trial ", number, " of ", study_id,
                                                    " has finished: it is ",
                                                    NameOf(kTrialStateNames, state)));
}

}  // namespace

namespace store_rows {

absl::Status CheckStudySubmission(const StudySubmission& submission) {
  if (submission.request_id.empty()) {
    return absl::InvalidArgumentError("a study needs a request id");
  }
  DCS_RETURN_IF_ERROR(run::ParseSearchSpaceYaml(submission.space, "the search space").status());
  DCS_RETURN_IF_ERROR(ValidateTpeOptions(submission.tpe));
  return ValidatePrunerOptions(submission.pruner);
}

int64_t InsertStudy(SQLite::Database& db, const StudySubmission& submission,
                    std::optional<int64_t> sweep, absl::Time now) {
  SQLite::Statement insert(db,
                           "INSERT INTO studies (request_id, name, space, sampler, seed, "
                           "direction, startup_trials, ei_candidates, multivariate, grouped, "
                           "constant_liar, created_at, pruner, median_percentile, "
                           "median_startup_trials, median_warmup_steps, median_interval_steps, "
                           "median_min_trials, halving_min_resource, halving_reduction_factor, "
                           "halving_min_early_stopping_rate, halving_bootstrap_count, sweep) "
                           "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
                           "?, ?, ?) RETURNING number");
  insert.bind(1, submission.request_id);
  insert.bind(2, submission.name);
  insert.bind(3, submission.space);
  insert.bind(4, std::string(NameOf(kSamplerKindNames, submission.sampler)));
  insert.bind(5, static_cast<int64_t>(submission.seed));
  insert.bind(6, std::string(NameOf(kDirectionNames, submission.direction)));
  const TpeOptions& tpe = submission.tpe;
  insert.bind(7, tpe.startup_trials);
  insert.bind(8, tpe.ei_candidates);
  insert.bind(9, tpe.parzen.multivariate ? 1 : 0);
  insert.bind(10, tpe.group ? 1 : 0);
  insert.bind(11, tpe.constant_liar ? 1 : 0);
  insert.bind(12, Micros(now));
  const PrunerOptions& pruner = submission.pruner;
  insert.bind(13, std::string(NameOf(kPrunerKindNames, pruner.kind)));
  insert.bind(14, pruner.median.percentile);
  insert.bind(15, pruner.median.startup_trials);
  insert.bind(16, pruner.median.warmup_steps);
  insert.bind(17, pruner.median.interval_steps);
  insert.bind(18, pruner.median.min_trials);
  if (pruner.halving.min_resource.has_value()) insert.bind(19, *pruner.halving.min_resource);
  insert.bind(20, pruner.halving.reduction_factor);
  insert.bind(21, pruner.halving.min_early_stopping_rate);
  insert.bind(22, pruner.halving.bootstrap_count);
  if (sweep.has_value()) insert.bind(23, *sweep);
  insert.executeStep();
  return insert.getColumn(0).getInt64();
}

void FailRunningStudyTrials(SQLite::Database& db, int64_t sweep, absl::Time now) {
  SQLite::Statement fail(db, "UPDATE study_trials SET state = 'failed', finished_at = ? "
                             "WHERE state = 'running' AND study = "
                             "(SELECT number FROM studies WHERE sweep = ?)");
  fail.bind(1, Micros(now));
  fail.bind(2, sweep);
  fail.exec();
}

void DeleteStudyRows(SQLite::Database& db, int64_t number) {
  DeleteRowAndChildren(db, "studies", number, "study",
                       {"study_trial_values", "study_trial_rungs", "study_trial_reports",
                        "study_trials"});
}

}  // namespace store_rows

absl::StatusOr<StudyRecord> StudyTable::CreateStudy(const StudySubmission& submission,
                                                    absl::Time now) {
  DCS_RETURN_IF_ERROR(CheckStudySubmission(submission));
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<StudyRecord> {
    SQLite::Statement existing(db, "SELECT number FROM studies WHERE request_id = ?");
    existing.bind(1, submission.request_id);
    const int64_t number = existing.executeStep()
                               ? existing.getColumn(0).getInt64()
                               : InsertStudy(db, submission, std::nullopt, now);
    DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, StudyId(number)));
    return row.record;
  });
}

absl::StatusOr<StudyRecord> StudyTable::GetStudy(absl::string_view study_id) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<StudyRecord> {
    DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, study_id));
    return row.record;
  });
}

absl::StatusOr<std::vector<StudyRecord>> StudyTable::ListStudies() {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<StudyRecord>> {
        std::vector<StudyRecord> studies;
        SQLite::Statement numbers(db, "SELECT number FROM studies ORDER BY number");
        while (numbers.executeStep()) {
          DCS_ASSIGN_OR_RETURN(StudyRow row,
                               FindStudy(db, StudyId(numbers.getColumn(0).getInt64())));
          studies.push_back(std::move(row.record));
        }
        return studies;
      });
}

absl::StatusOr<StudyTrial> StudyTable::AskTrial(absl::string_view study_id,
                                                absl::string_view request_id, absl::Time now) {
  if (request_id.empty()) return absl::InvalidArgumentError("an ask needs a request id");
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<StudyTrial> {
    DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, study_id));
    const int64_t study = row.number;
    const std::vector<StudyTrial>& trials = row.trials;
    SQLite::Statement asked(db,
                            "SELECT number FROM study_trials WHERE study = ? AND request_id = ?");
    asked.bind(1, study);
    asked.bind(2, std::string(request_id));
    if (asked.executeStep()) {
      DCS_ASSIGN_OR_RETURN(const StudyTrial* asked_before,
                           FindTrial(row, asked.getColumn(0).getInt64()));
      return *asked_before;
    }
    StudyTrial trial{.number = trials.empty() ? 0 : trials.back().number + 1,
                     .state = TrialState::kRunning,
                     .value = kNaN};
    trial.values = MakeSampler(row.record.submission)->Sample(row.space, trials, trial.number);

    SQLite::Statement insert(db,
                             "INSERT INTO study_trials (study, number, request_id, state, "
                             "created_at) VALUES (?, ?, ?, 'running', ?)");
    insert.bind(1, study);
    insert.bind(2, trial.number);
    insert.bind(3, std::string(request_id));
    insert.bind(4, Micros(now));
    insert.exec();
    SQLite::Statement value(db,
                            "INSERT INTO study_trial_values (study, trial, name, value) "
                            "VALUES (?, ?, ?, ?)");
    for (const auto& [name, v] : trial.values) {
      value.bind(1, study);
      value.bind(2, trial.number);
      value.bind(3, name);
      value.bind(4, v);
      value.exec();
      value.reset();
    }
    return trial;
  });
}

absl::StatusOr<StudyTrial> StudyTable::TellTrial(absl::string_view study_id, int64_t number,
                                                 TrialState state, double value, absl::Time now) {
  if (state == TrialState::kRunning) {
    return absl::InvalidArgumentError("a trial is told complete, pruned or failed, not running");
  }
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<StudyTrial> {
    DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, study_id));
    DCS_ASSIGN_OR_RETURN(StudyTrial* const found, FindTrial(row, number));
    StudyTrial& trial = *found;
    const TrialState current = trial.state;
    const TrialState told =
        state == TrialState::kComplete && std::isnan(value) ? TrialState::kFailed : state;
    // Told again as it was (a retry whose first answer was lost): nothing changes.
    if (current == told && (told != TrialState::kComplete || trial.value == value)) return trial;
    DCS_RETURN_IF_ERROR(RequireRunning(current, study_id, number));
    trial.state = told;
    trial.value = trial.state == TrialState::kComplete ? value
                  : trial.state == TrialState::kPruned && !trial.reported.empty()
                      ? trial.reported.rbegin()->second
                      : kNaN;
    SQLite::Statement update(db,
                             "UPDATE study_trials SET state = ?, value = ?, finished_at = ? "
                             "WHERE study = ? AND number = ?");
    update.bind(1, std::string(NameOf(kTrialStateNames, trial.state)));
    BindDoubleOrNull(update, 2, trial.value);
    update.bind(3, Micros(now));
    update.bind(4, row.number);
    update.bind(5, number);
    update.exec();
    return trial;
  });
}

absl::StatusOr<bool> StudyTable::ReportTrial(absl::string_view study_id, int64_t number,
                                             int64_t step, double value) {
  return connection_.Transaction([&](SQLite::Database& db) -> absl::StatusOr<bool> {
    DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, study_id));
    DCS_ASSIGN_OR_RETURN(StudyTrial* const found, FindTrial(row, number));
    StudyTrial& trial = *found;
    DCS_RETURN_IF_ERROR(RequireRunning(trial.state, study_id, number));
    const int64_t study = row.number;
    SQLite::Statement insert(db,
                             "INSERT OR IGNORE INTO study_trial_reports (study, trial, step, "
                             "value) VALUES (?, ?, ?, ?)");
    insert.bind(1, study);
    insert.bind(2, number);
    insert.bind(3, step);
    BindDoubleOrNull(insert, 4, value);
    insert.exec();
    trial.reported.try_emplace(step, value);  // as stored: a repeated step keeps the first

    const StudySubmission& s = row.record.submission;
    const std::vector<StudyTrial>& trials = row.trials;
    switch (s.pruner.kind) {
      case PrunerKind::kNone:
        return false;
      case PrunerKind::kMedian:
        return MedianPrune(trial, trials, s.direction, s.pruner.median);
      case PrunerKind::kSuccessiveHalving:
        break;
    }
    std::map<int64_t, std::map<int, double>> rungs;
    SQLite::Statement read(db,
                           "SELECT trial, rung, value FROM study_trial_rungs WHERE study = ?");
    read.bind(1, study);
    while (read.executeStep()) {
      rungs[read.getColumn(0).getInt64()][read.getColumn(1).getInt()] =
          read.getColumn(2).getDouble();
    }
    std::vector<std::map<int, double>> others;
    for (const auto& [other, recorded] : rungs) {
      if (other != number) others.push_back(recorded);
    }
    const HalvingDecision decision =
        SuccessiveHalvingPrune(trial, rungs[number], others, trials, s.direction, s.pruner.halving);
    SQLite::Statement write(db,
                            "INSERT OR IGNORE INTO study_trial_rungs (study, trial, rung, value) "
                            "VALUES (?, ?, ?, ?)");
    for (const auto& [rung, recorded] : decision.rungs) {
      write.bind(1, study);
      write.bind(2, number);
      write.bind(3, rung);
      write.bind(4, recorded);
      write.exec();
      write.reset();
    }
    return decision.prune;
  });
}

absl::StatusOr<std::vector<StudyTrial>> StudyTable::ListStudyTrials(absl::string_view study_id) {
  return connection_.Transaction(
      [&](SQLite::Database& db) -> absl::StatusOr<std::vector<StudyTrial>> {
        DCS_ASSIGN_OR_RETURN(StudyRow row, FindStudy(db, study_id));
        return std::move(row.trials);
      });
}

}  // namespace dcs::coordinator
