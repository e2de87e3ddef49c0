// Copyright 2026 The DCS Authors.
#include "coordinator/study_sweep.h"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "coordinator/iqm.h"
#include "coordinator/run_files.h"
#include "coordinator/run_submission.h"
#include "env/observe_mode.h"
#include "run/evaluation_log.h"
#include "run/run_directory.h"
#include "run/study_config.h"

namespace dcs::coordinator {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Mean or IQM over seeds, as `objective` summarises them.
double OverSeeds(StudyObjective objective, const std::vector<double>& values) {
  if (objective == StudyObjective::kLastIqm) {
    absl::StatusOr<IqmSummary> iqm = SummarizeIqm(values);
    return iqm.ok() ? iqm->iqm : kNaN;
  }
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

// The steps where the stages of the run `spec` end, the last one's (the end) excluded.
std::vector<int64_t> StageBoundaries(const run::RunSpec& spec) {
  std::vector<int64_t> boundaries;
  int64_t step = 0;
  for (size_t k = 0; k + 1 < spec.stages.size(); ++k) {
    step += spec.stages[k].steps;
    boundaries.push_back(step);
  }
  return boundaries;
}

// A trial of the sweep as the step sees it: its index in the sweep and its runs, by seed.
struct QueuedTrial {
  int index = 0;
  std::vector<RunRecord> runs;
};

class Step {
 public:
  Step(Store& store, const std::string& data_dir, CompletedRunLogs& logs,
       const SweepRecord& sweep, const StudySweepSpec& spec, absl::Time now)
      : store_(store), data_dir_(data_dir), logs_(logs), sweep_(sweep), spec_(spec), now_(now) {}

  absl::StatusOr<StudySweepStep> Run() {
    DCS_ASSIGN_OR_RETURN(std::vector<StudyTrial> trials,
                         store_.studies().ListStudyTrials(sweep_.study_id));
    DCS_ASSIGN_OR_RETURN(const std::vector<RunRecord> runs,
                         store_.sweeps().ListSweepRuns(sweep_.id));
    std::map<std::pair<int64_t, bool>, QueuedTrial> queued;  // (study trial, retrain) -> runs
    for (size_t i = 0; i < sweep_.trials.size(); ++i) {
      const TrialRecord& trial = sweep_.trials[i];
      if (trial.study_trial.has_value()) {
        queued[{*trial.study_trial, trial.retrain}].index = static_cast<int>(i);
      }
    }
    std::map<int, std::vector<RunRecord>> runs_of;  // sweep trial index -> its runs
    for (const RunRecord& run : runs) {
      if (run.trial.has_value()) runs_of[*run.trial].push_back(run);
    }
    for (auto& [key, trial] : queued) trial.runs = std::move(runs_of[trial.index]);

    int running = 0;
    for (StudyTrial& trial : trials) {
      if (trial.state != TrialState::kRunning) continue;
      auto found = queued.find({trial.number, false});
      if (found == queued.end()) {  // asked, but the step that asked stopped before queueing it
        DCS_RETURN_IF_ERROR(Queue(trial, /*retrain=*/false));
      } else {
        DCS_RETURN_IF_ERROR(Follow(trial, found->second.runs));
      }
      running += trial.state == TrialState::kRunning ? 1 : 0;
    }
    for (int64_t number = static_cast<int64_t>(trials.size());
         number < spec_.trials && running < spec_.parallel && !cancelled_; ++number) {
      DCS_ASSIGN_OR_RETURN(
          StudyTrial trial,
          store_.studies().AskTrial(sweep_.study_id,
                                    absl::StrCat(sweep_.request_id, "/ask/", number), now_));
      DCS_RETURN_IF_ERROR(Queue(trial, /*retrain=*/false));
      ++done_.asked;
      running += trial.state == TrialState::kRunning ? 1 : 0;
      trials.push_back(std::move(trial));
    }
    if (static_cast<int64_t>(trials.size()) < spec_.trials || running > 0 || cancelled_) {
      return done_;
    }

    for (StudyTrial* trial : Best(trials, spec_.retrain_top_k)) {
      DCS_RETURN_IF_ERROR(Queue(*trial, /*retrain=*/true));
      done_.retrained += queued.contains({trial->number, true}) ? 0 : 1;
    }
    DCS_RETURN_IF_ERROR(store_.sweeps().CloseSweep(sweep_.id, now_));
    done_.closed = true;
    return done_;
  }

 private:
  // The `k` best complete trials, best first (equals: the lower number first).
  static std::vector<StudyTrial*> Best(std::vector<StudyTrial>& trials, int k) {
    std::vector<StudyTrial*> complete;
    for (StudyTrial& trial : trials) {
      if (trial.state == TrialState::kComplete) complete.push_back(&trial);
    }
    std::stable_sort(complete.begin(), complete.end(),
                     [](const StudyTrial* a, const StudyTrial* b) {
                       return IsBetter(Direction::kMaximize, a->value, b->value);
                     });
    complete.resize(std::min<size_t>(complete.size(), static_cast<size_t>(k)));
    return complete;
  }

  // Queues `trial`'s runs (the search's seeds, or the retrain's), writing their directories. A
  // trial whose run config does not validate fails.
  absl::Status Queue(StudyTrial& trial, bool retrain) {
    const std::string condition = StudyTrialCondition(trial.number, retrain);
    absl::StatusOr<std::string> config = run::TrialRunConfig(spec_.sweep.trials.front().config,
                                                             condition, spec_.space, trial.values);
    std::vector<run::RunRequest> requests;
    std::vector<RunSubmission> submissions;
    const std::vector<uint64_t>& seeds = retrain ? spec_.retrain_seeds : spec_.sweep.seeds;
    for (uint64_t seed : seeds) {
      if (!config.ok()) break;
      absl::StatusOr<run::RunRequest> request = CheckSubmittedRun(*config, condition, seed);
      if (!request.ok()) {
        config = request.status();
        break;
      }
      submissions.push_back(
          SubmissionOf(*request, absl::StrCat(sweep_.request_id, "/", condition, "/", seed)));
      requests.push_back(*std::move(request));
    }
    if (!config.ok()) return Tell(trial, TrialState::kFailed, kNaN);
    const run::SweepTrial& base = spec_.sweep.trials.front();
    absl::StatusOr<std::vector<RunRecord>> runs =
        store_.sweeps().AddSweepTrial(sweep_.id,
                             {.condition = condition,
                              .family = base.family,
                              .observe = std::string(NameOf(env::kObserveModeNames, base.observe)),
                              .study_trial = trial.number,
                              .retrain = retrain},
                             submissions, now_);
    if (absl::IsFailedPrecondition(runs.status()) && !retrain) {
      // The sweep was cancelled since this step read it: the trial asked meanwhile fails, as
      // the cancel failed the others, and the step asks no more.
      cancelled_ = true;
      return Tell(trial, TrialState::kFailed, kNaN);
    }
    if (!runs.ok()) return runs.status();
    for (size_t i = 0; i < runs->size() && i < requests.size(); ++i) {
      requests[i].dir = RunDirectory(data_dir_, (*runs)[i].id);
      DCS_RETURN_IF_ERROR(run::CreateRunDirectory(requests[i]));
    }
    return absl::OkStatus();
  }

  // Tells a trial whose runs all ended its objective (failed if any run did not complete), or
  // reports its objective at the stage boundaries its runs have all passed (a complete trial's
  // too, before it is told, so that the pruner compares with every complete trial).
  absl::Status Follow(StudyTrial& trial, const std::vector<RunRecord>& runs) {
    const bool ended = std::all_of(runs.begin(), runs.end(),
                                   [](const RunRecord& run) { return IsTerminal(run.state); });
    const bool pruning = spec_.study.pruner.kind != PrunerKind::kNone;
    if (ended) {
      std::vector<v1::EvaluationLog> logs;
      for (const RunRecord& run : runs) {
        if (run.state != RunState::kCompleted) return Tell(trial, TrialState::kFailed, kNaN);
        DCS_ASSIGN_OR_RETURN(logs.emplace_back(), logs_.Get(run));
      }
      if (pruning) {
        DCS_RETURN_IF_ERROR(Report(trial, Boundaries(runs), logs, /*ended=*/true).status());
      }
      return Tell(trial, TrialState::kComplete, TrialObjective(spec_.objective, logs));
    }
    if (!pruning) return absl::OkStatus();
    const std::vector<int64_t> boundaries = Boundaries(runs);
    const auto next = std::find_if(boundaries.begin(), boundaries.end(), [&](int64_t boundary) {
      return !trial.reported.contains(boundary);
    });
    if (next == boundaries.end()) return absl::OkStatus();
    for (const RunRecord& run : runs) {
      if (run.progress.evaluation_step.value_or(-1) < *next) return absl::OkStatus();
    }
    std::vector<v1::EvaluationLog> logs;
    for (const RunRecord& run : runs) {
      absl::StatusOr<v1::EvaluationLog> log =
          run.state == RunState::kCompleted
              ? logs_.Get(run)
              : run::ReadEvaluationLog(RunDirectory(data_dir_, run.id));
      if (!log.ok()) return absl::OkStatus();  // its checkpoint is on its way: next step
      logs.push_back(*std::move(log));
    }
    DCS_ASSIGN_OR_RETURN(const std::optional<double> pruned_at,
                         Report(trial, boundaries, logs, /*ended=*/false));
    if (!pruned_at.has_value()) return absl::OkStatus();
    for (const RunRecord& run : runs) {
      if (IsTerminal(run.state)) continue;
      absl::Status cancelled = store_.runs().CancelRun(run.id, now_).status();
      if (!cancelled.ok() && !absl::IsFailedPrecondition(cancelled)) return cancelled;
    }
    return Tell(trial, TrialState::kPruned, *pruned_at);
  }

  // The stage boundaries of the trial of `runs` (its config is every run's, but for the seed).
  static std::vector<int64_t> Boundaries(const std::vector<RunRecord>& runs) {
    absl::StatusOr<run::RunRequest> request =
        CheckSubmittedRun(runs.front().submission.config, runs.front().id, std::nullopt);
    return request.ok() ? StageBoundaries(request->spec) : std::vector<int64_t>{};
  }

  // Reports the trial's objective at each of its stage `boundaries` not yet reported that every
  // one of `logs` has passed. Returns the value it was pruned at, if the pruner said so (never
  // for a trial whose runs `ended`: it is complete whatever the pruner says).
  absl::StatusOr<std::optional<double>> Report(StudyTrial& trial,
                                               const std::vector<int64_t>& boundaries,
                                               const std::vector<v1::EvaluationLog>& logs,
                                               bool ended) {
    for (int64_t boundary : boundaries) {
      if (trial.reported.contains(boundary)) continue;
      const std::optional<double> value = ObjectiveAt(spec_.objective, logs, boundaries, boundary);
      if (!value.has_value()) break;
      DCS_ASSIGN_OR_RETURN(const bool prune, store_.studies().ReportTrial(
                                                 sweep_.study_id, trial.number, boundary, *value));
      trial.reported[boundary] = *value;
      ++done_.reported;
      if (prune && !ended) return value;
    }
    return std::nullopt;
  }

  absl::Status Tell(StudyTrial& trial, TrialState state, double value) {
    DCS_ASSIGN_OR_RETURN(
        trial, store_.studies().TellTrial(sweep_.study_id, trial.number, state, value, now_));
    ++done_.told;
    return absl::OkStatus();
  }

  Store& store_;
  const std::string& data_dir_;
  CompletedRunLogs& logs_;
  const SweepRecord& sweep_;
  const StudySweepSpec& spec_;
  const absl::Time now_;
  StudySweepStep done_;
  bool cancelled_ = false;  // found cancelled while it stepped
};

}  // namespace

std::string StudyTrialCondition(int64_t number, bool retrain) {
  return absl::StrFormat("T%03d%s", number, retrain ? " retrain" : "");
}

double TrialObjective(StudyObjective objective, const std::vector<v1::EvaluationLog>& logs) {
  std::vector<double> values;
  for (const v1::EvaluationLog& log : logs) {
    values.push_back(objective == StudyObjective::kBestAnytime ? log.best_anytime() : log.last());
  }
  return values.empty() ? kNaN : OverSeeds(objective, values);
}

std::optional<double> ObjectiveAt(StudyObjective objective,
                                  const std::vector<v1::EvaluationLog>& logs,
                                  const std::vector<int64_t>& boundaries, int64_t step) {
  std::vector<double> values;
  for (const v1::EvaluationLog& log : logs) {
    std::optional<double> at_step;
    double best = -std::numeric_limits<double>::infinity();
    for (const v1::Evaluation& evaluation : log.evaluations()) {
      if (evaluation.step() > step) break;
      if (evaluation.step() == step) at_step = evaluation.avg_combined();
      if (std::find(boundaries.begin(), boundaries.end(), evaluation.step()) != boundaries.end() ||
          evaluation.step() == step) {
        best = std::max(best, evaluation.avg_combined());
      }
    }
    if (!at_step.has_value()) return std::nullopt;
    values.push_back(objective == StudyObjective::kBestAnytime ? best : *at_step);
  }
  return OverSeeds(objective, values);
}

absl::StatusOr<StudySweepStep> AdvanceStudySweep(Store& store, const std::string& data_dir,
                                                 CompletedRunLogs& logs, const SweepRecord& sweep,
                                                 const StudySweepSpec& spec, absl::Time now) {
  return Step(store, data_dir, logs, sweep, spec, now).Run();
}

}  // namespace dcs::coordinator
