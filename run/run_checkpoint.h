// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_CHECKPOINT_H_
#define DCS_RUN_RUN_CHECKPOINT_H_

// Checkpoints of a training run: everything needed to resume it exactly. Every random stream of
// a run is derived from its seed and counters, so the state is the learner's (weights, Adam's
// moments, update count), the counters, each environment slot's running episode (to replay it)
// and the evaluations so far.
//
// Layout, in the run's output directory (spec/operations.md §7.3):
//   checkpoints/<timesteps>/learner.bin   PpoLearner::SaveState
//   checkpoints/<timesteps>/run.yaml      counters, journals, evaluations
//   checkpoints/<timesteps>/MANIFEST      sha256 of both, written after them
//   checkpoints/latest                    the newest <timesteps>, written last
// Each file is written atomically (common/atomic_file.h); the newest `keep` checkpoints are
// kept. Thread-compatible.

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/evaluation.h"
#include "actor/rollout_collector.h"

namespace dcs::run {

struct RunState {
  int64_t timesteps = 0;  // environment steps collected
  int64_t rollouts = 0;   // rollouts collected (and updates made)
  std::vector<actor::SlotJournal> journals;
  std::vector<double> recent_returns;  // the last finished training episodes' returns
  std::vector<actor::EvaluationResult> evaluations;
};

struct Checkpoint {
  std::string name;  // "<timesteps>"
  RunState state;
  std::string learner;  // PpoLearner::SaveState bytes
};

// Writes `state` and `learner` as checkpoint `<state.timesteps>` of `run_dir`, points `latest`
// at it, and deletes all but the newest `keep`. Errors name the file (RESOURCE_EXHAUSTED for a
// full disk); the previous checkpoint stays valid whatever fails.
absl::Status WriteCheckpoint(const std::string& run_dir, const RunState& state,
                             const std::string& learner, int keep);

// The newest checkpoint of `run_dir` that reads back whole: if the one `latest` names is
// corrupt or truncated (checksum, YAML), the next older one. NOT_FOUND if there is none;
// DATA_LOSS if every checkpoint is corrupt.
absl::StatusOr<Checkpoint> ReadLatestCheckpoint(const std::string& run_dir);

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_CHECKPOINT_H_
