// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_results.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "common/status_macros.h"
#include "coordinator/run_files.h"
#include "run/evaluation_log.h"

namespace dcs::coordinator {

absl::StatusOr<v1::EvaluationLog> CompletedRunLogs::Get(const RunRecord& run) {
  {
    absl::MutexLock lock(&mu_);
    if (auto it = logs_.find(run.id); it != logs_.end()) return it->second;
  }
  absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(RunDirectory(data_dir_, run.id));
  if (!log.ok()) {
    return absl::DataLossError(absl::StrCat("the evaluation log of ", run.id,
                                            " is unreadable: ", log.status().message()));
  }
  for (v1::Evaluation& evaluation : *log->mutable_evaluations()) {
    for (v1::ContextEvaluation& context : *evaluation.mutable_contexts()) {
      context.clear_returns();
    }
  }
  absl::MutexLock lock(&mu_);
  return logs_.try_emplace(run.id, *std::move(log)).first->second;
}

void CompletedRunLogs::Forget(const std::string& run_id) {
  absl::MutexLock lock(&mu_);
  logs_.erase(run_id);
}

void KeepScoresOnly(v1::EvaluationLog& log) {
  const int last = log.evaluations_size() - 1;
  const int best = log.best_anytime_index();
  google::protobuf::RepeatedPtrField<v1::Evaluation> kept;
  if (best >= 0 && best < last) *kept.Add() = std::move(*log.mutable_evaluations(best));
  if (last >= 0) *kept.Add() = std::move(*log.mutable_evaluations(last));
  for (v1::Evaluation& evaluation : kept) evaluation.clear_contexts();
  // An index out of range stays out of range, for the report to refuse as before.
  if (best >= 0 && best <= last) log.set_best_anytime_index(best == last ? kept.size() - 1 : 0);
  *log.mutable_evaluations() = std::move(kept);
}

absl::StatusOr<v1::SweepResults> CollectSweepResults(const SweepRecord& sweep,
                                                     const std::vector<RunRecord>& runs,
                                                     CompletedRunLogs& logs, bool scores_only) {
  v1::SweepResults results;
  results.set_sweep_id(sweep.id);
  results.set_name(sweep.name);
  results.set_seeds(sweep.seeds);
  results.set_spec(sweep.spec);
  results.set_study_id(sweep.study_id);
  for (const TrialRecord& trial : sweep.trials) {
    v1::TrialResults& out = *results.add_trials();
    out.set_condition(trial.condition);
    out.set_family(trial.family);
    out.set_observe(trial.observe);
    if (trial.study_trial.has_value()) out.set_study_trial(*trial.study_trial);
    out.set_retrain(trial.retrain);
  }
  std::vector<const RunRecord*> completed;
  for (const RunRecord& run : runs) {
    if (run.state != RunState::kCompleted || !run.trial.has_value()) continue;
    if (*run.trial < 0 || *run.trial >= results.trials_size()) continue;
    completed.push_back(&run);
  }
  std::sort(completed.begin(), completed.end(), [](const RunRecord* a, const RunRecord* b) {
    return a->submission.seed < b->submission.seed;
  });
  for (const RunRecord* run : completed) {
    v1::EvaluationLog& log = *results.mutable_trials(*run->trial)->add_runs();
    DCS_ASSIGN_OR_RETURN(log, logs.Get(*run));
    if (scores_only) KeepScoresOnly(log);
  }
  return results;
}

}  // namespace dcs::coordinator
