// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STUDY_SWEEP_H_
#define DCS_COORDINATOR_STUDY_SWEEP_H_

// Drives a study sweep (coordinator/study_sweep_spec.h) on the run store: asks its study for
// trials, trains each with the sweep's seeds, tells the study each trial's objective, reports
// the objective at stage boundaries to its pruner (cancelling a pruned trial's runs), and once
// every trial has finished retrains the best. Each step is a function of what the store and the
// runs' directories hold, so the coordinator calls it again and again (after a restart too) and
// a step cut short by a crash is finished by the next: a trial asked but not yet queued is
// queued, a trial queued again is found (AddSweepTrial), a tell repeated is answered as the
// first. So no trial is lost or trained twice. Thread-compatible: one caller per sweep at a time.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/sweep_results.h"
#include "dcs/v1/evaluation.pb.h"

namespace dcs::coordinator {

// What one step did.
struct StudySweepStep {
  int asked = 0;        // new trials queued
  int told = 0;         // trials finished (complete, failed or pruned)
  int reported = 0;     // intermediate values reported
  int retrained = 0;    // retrain trials queued
  bool closed = false;  // the sweep will add no more trials
};

// One step of the open study sweep `sweep` of spec `spec` (its spec text, parsed by
// ParseStudySweepYaml), whose runs' directories are in `data_dir` (coordinator/run_files.h) and
// whose completed runs' logs `logs` reads. Errors: the store's, and DATA_LOSS for a completed run
// whose evaluation log is missing.
absl::StatusOr<StudySweepStep> AdvanceStudySweep(Store& store, const std::string& data_dir,
                                                 CompletedRunLogs& logs, const SweepRecord& sweep,
                                                 const StudySweepSpec& spec, absl::Time now);

// The condition name of study trial `number` in its sweep ("T007"), and of its retrain
// ("T007 retrain").
std::string StudyTrialCondition(int64_t number, bool retrain);

// The objective of a trial from its complete runs' evaluation logs (one per seed), as
// `objective` defines it (coordinator/study_sweep_spec.h). NaN for no logs.
double TrialObjective(StudyObjective objective, const std::vector<v1::EvaluationLog>& logs);

// The objective of a trial from its runs' evaluation logs (one per seed), as `objective` defines
// it, as it stood at training step `step` (evaluations after it ignored; best_anytime: among
// the evaluations at `boundaries` and at `step`). nullopt if a log has no evaluation at `step`
// yet.
std::optional<double> ObjectiveAt(StudyObjective objective,
                                  const std::vector<v1::EvaluationLog>& logs,
                                  const std::vector<int64_t>& boundaries, int64_t step);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STUDY_SWEEP_H_
