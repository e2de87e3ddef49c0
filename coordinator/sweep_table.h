// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_SWEEP_TABLE_H_
#define DCS_COORDINATOR_SWEEP_TABLE_H_

// The store's sweeps (coordinator/store.h holds the whole store): a sweep's row, its trials,
// and its runs, which are ordinary runs (coordinator/run_table.h) that name their sweep and
// trial. A study sweep drives a study (coordinator/study_table.h) created with it, and adds
// its trials as the study asks for them.
//
// Thread-safe: every call is one transaction on the store's one connection; it returns after
// the transaction committed. Times are passed in (tests drive the clock).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "absl/types/span.h"
#include "coordinator/run_state.h"
#include "coordinator/run_table.h"
#include "coordinator/study_table.h"

namespace dcs::coordinator {

// One trial of a sweep: a condition in one observation mode (run/sweep_spec.h), or in a study
// sweep a trial of its study (its search, or its retrain with more seeds).
struct TrialRecord {
  std::string condition;
  std::string family;   // "static", a schedule family, or "multi_stage"
  std::string observe;  // none | initial | live
  std::optional<int64_t> study_trial;  // the study trial it trains, in a study sweep
  bool retrain = false;                // a study trial retrained after the search
};

// A sweep as submitted: its trials and one run per trial and seed.
struct SweepSubmission {
  std::string request_id;  // client-chosen; a repeated id returns the sweep it created
  std::string name;
  std::string spec;        // the spec's text as submitted
  int seeds = 0;           // runs per trial
  std::vector<TrialRecord> trials;
  struct Run {
    int trial = 0;  // index into `trials`
    RunSubmission run;
  };
  // Queued in this order (and so started in it, within the sweep's fair share): seed-major,
  // so a sweep's early results cover every trial.
  std::vector<Run> runs;
  // A study sweep (coordinator/study_sweep.h): the study it drives, created with it. Its trials
  // and runs are added as the study asks for them (AddSweepTrial), so it has none at first.
  std::optional<StudySubmission> study;
};

struct SweepRecord {
  std::string id;  // "sweep-<n>"
  std::string request_id;
  std::string name;
  std::string spec;
  int seeds = 0;
  std::vector<TrialRecord> trials;
  SweepState state = SweepState::kQueued;  // derived from its runs and `open` (SweepStateOf)
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  std::string study_id;  // the study it drives ("study-<n>"); empty for a plain sweep
  bool open = false;     // a study sweep that will add trials (until CloseSweep)
  absl::Time created_at;
  absl::Time updated_at;
};

// A sweep removed for good, as it was, with its runs (SweepTable::DeleteSweeps).
struct RemovedSweep {
  SweepRecord sweep;
  std::vector<RunRecord> runs;  // oldest first
};

class SweepTable {
 public:
  SweepTable(const SweepTable&) = delete;
  SweepTable& operator=(const SweepTable&) = delete;

  // Queues a sweep's runs, all of them or (on an error) none, or returns the sweep
  // `submission.request_id` already created. A study sweep is created open, with its study
  // (named as the sweep, its request id the sweep's) and no trials. INVALID_ARGUMENT for an
  // empty request id, no trials (in a plain sweep), seeds < 1, a run naming no trial, a run
  // RunTable::SubmitRun refuses, or a study StudyTable::CreateStudy refuses.
  absl::StatusOr<SweepRecord> SubmitSweep(const SweepSubmission& submission, absl::Time now);
  // Adds a trial of study trial `trial.study_trial` and its runs to the open study sweep, all of
  // it or nothing, and returns its runs in `runs`' order; a trial already added (the same study
  // trial, retrain or not) is not added again, and its runs are returned. INVALID_ARGUMENT for a
  // trial without a study trial or with no runs, or runs RunTable::SubmitRun refuses;
  // NOT_FOUND; FAILED_PRECONDITION if the sweep is not open.
  absl::StatusOr<std::vector<RunRecord>> AddSweepTrial(absl::string_view sweep_id,
                                                       const TrialRecord& trial,
                                                       const std::vector<RunSubmission>& runs,
                                                       absl::Time now);
  // The study sweep will add no more trials. NOT_FOUND; idempotent.
  absl::Status CloseSweep(absl::string_view sweep_id, absl::Time now);
  // The open study sweeps, oldest first.
  absl::StatusOr<std::vector<SweepRecord>> ListOpenSweeps();
  // NOT_FOUND for an unknown id.
  absl::StatusOr<SweepRecord> GetSweep(absl::string_view sweep_id);
  // Every sweep, oldest first.
  absl::StatusOr<std::vector<SweepRecord>> ListSweeps();
  // The sweep's runs, oldest first. NOT_FOUND for an unknown sweep.
  absl::StatusOr<std::vector<RunRecord>> ListSweepRuns(absl::string_view sweep_id);
  // Cancels every queued or running run of the sweep; a study sweep is closed and its running
  // study trials fail. NOT_FOUND; FAILED_PRECONDITION if none of its runs was queued or running
  // and it was not open.
  absl::StatusOr<SweepRecord> CancelSweep(absl::string_view sweep_id, absl::Time now);
  // Removes sweeps for good, every one of `sweep_ids` or, on an error, none, with their trials,
  // their runs as RunTable::DeleteRuns removes them, and a study sweep's study; returns them as
  // they were, in `sweep_ids`' order, each once. Their ids (and their runs' and study's) are
  // never given again. Their runs' directories are the caller's to remove once this returns
  // (coordinator/run_removal.h). INVALID_ARGUMENT for no id; NOT_FOUND for an unknown one;
  // FAILED_PRECONDITION, naming it, for a sweep with a run queued or running, one that still
  // adds trials (an open study sweep), or a run CheckRemovable refuses otherwise.
  absl::StatusOr<std::vector<RemovedSweep>> DeleteSweeps(absl::Span<const std::string> sweep_ids);
  // Queues the sweep's failed runs again (each resumes from its last checkpoint, as a run whose
  // learner was lost does) and returns how many. NOT_FOUND; FAILED_PRECONDITION if none failed,
  // or for a study sweep (its study was told those trials failed).
  absl::StatusOr<std::pair<SweepRecord, int>> RetrySweep(absl::string_view sweep_id,
                                                         absl::Time now);

 private:
  friend class Store;
  explicit SweepTable(internal::StoreConnection& connection) : connection_(connection) {}

  internal::StoreConnection& connection_;  // the Store's, which owns this table too
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_SWEEP_TABLE_H_
