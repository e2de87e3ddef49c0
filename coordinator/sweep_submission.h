// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SWEEP_SUBMISSION_H_
#define DCS_COORDINATOR_SWEEP_SUBMISSION_H_

// A sweep spec submitted remotely, checked whole before anything is stored: read once and
// validated (run/sweep_spec_yaml.h: every problem with its path and line), then each of its
// trials planned as a run submitted alone is (coordinator/run_submission.h), so nothing is
// queued that no learner could train. Each run is made from its trial's spec and text as read
// (run/seeded_runs.h), not read again. Thread-safe (pure functions).

#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/sweep_table.h"
#include "run/run_directory.h"

namespace dcs::coordinator {

struct ExpandedSweep {
  SweepSubmission submission;
  // One per submission.runs entry, in the same order: the run's spec and config, to write its
  // directory once it has an id.
  std::vector<run::RunRequest> requests;
  // A study sweep's spec as read, for the study's driver (coordinator/study_sweep_driver.h).
  std::optional<StudySweepSpec> study;
};

// The sweep of `spec_text` (named `spec_name` in errors), named by the spec or else
// `default_name`, its runs' request ids derived from `request_id` (so a retried submission
// names the same runs). Runs are queued seed-major: every trial's first seed, then every
// trial's second, so early results cover the whole grid. A study sweep's submission holds its
// study (its request id the sweep's) and no trials or runs (coordinator/study_sweep.h adds them).
// INVALID_ARGUMENT as ParseSweepSpecYaml (ParseStudySweepYaml for a study sweep), or as
// CheckPlannable naming the trial.
absl::StatusOr<ExpandedSweep> ExpandSweep(const std::string& spec_text,
                                          const std::string& spec_name,
                                          const std::string& default_name,
                                          const std::string& request_id);

// What `sweep` would be once submitted, as a record: its name, seeds and trials, and every run
// queued (`submit --dry-run`, offline or on the coordinator).
SweepRecord SweepPreview(const ExpandedSweep& sweep);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SWEEP_SUBMISSION_H_
