// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STORE_COUNTS_H_
#define DCS_COORDINATOR_STORE_COUNTS_H_

// What the coordinator's metrics show of its store (Store::Counts, read at each scrape): runs by
// state, the work waiting, each queued or running run's progress and scores, each shown sweep's
// runs by state and best trial so far, the store's size. Plain data.
//
// Bounded: one LiveRun per run queued or running; one SweepCounts per sweep with work ahead
// (runs queued or running, or a study adding trials) and per sweep among the kRecentSweeps
// most recent by id, ended or not, so that a sweep's final tally and best trial stay readable
// after it ends while the series stay few.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/time/time.h"
#include "coordinator/checkpoint_table.h"
#include "coordinator/run_state.h"

namespace dcs::coordinator {

inline constexpr int kRecentSweeps = 20;

// A run queued or running.
struct LiveRun {
  std::string run_id;
  std::string sweep_id;  // these three empty for a run alone
  std::string condition;
  std::string observe;
  RunState state = RunState::kQueued;
  int64_t timesteps = 0;  // the furthest step its learners reached (RunTable::ReportProgress)
  int64_t total_timesteps = 0;
  // Its latest and best evaluation as its checkpoints brought them (NaN where none is known:
  // a split without contexts, no finite best); nullopt before the first.
  std::optional<EvaluationScores> scores;
  // Running: when its latest checkpoint was indexed, or, before its first, when its learner
  // lease was granted; nullopt for a queued run, which no learner is expected to checkpoint.
  std::optional<absl::Time> checkpointed_at;
};

// A trial of a sweep, with a score.
struct TrialScore {
  std::string condition;
  std::string observe;
  double score = 0;
};

// A sweep shown in metrics.
struct SweepCounts {
  std::string sweep_id;
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  int64_t steps_remaining = 0;  // environment steps its queued and running runs have left
  // Its best trial so far as `dcs watch` names it (HighestIqm over each trial's completed
  // runs' last avg_combined) with that IQM; nullopt before a run of it completed with one.
  std::optional<TrialScore> best;
};

struct StoreCounts {
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  int64_t free_learner_leases = 0;  // runs waiting for a learner
  int64_t free_slot_leases = 0;     // slots of running runs waiting for an actor
  // Evaluation jobs waiting for an actor: of running runs, and cells of grid evaluations; and
  // when the evaluation of the oldest of them was submitted (nullopt: none waits).
  int64_t free_evaluation_jobs = 0;
  std::optional<absl::Time> oldest_free_evaluation;
  std::vector<LiveRun> live_runs;  // in run order
  std::vector<SweepCounts> sweeps;  // in sweep order
  int64_t store_bytes = 0;  // the database file and its write-ahead log
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STORE_COUNTS_H_
