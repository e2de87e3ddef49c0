// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_RUN_CHECKPOINT_H_
#define DCS_RUN_RUN_CHECKPOINT_H_

// Checkpoints of a training run: everything needed to resume it exactly. Every random stream of
// a run is derived from its seed and counters, so the state is the learner's (weights, Adam's
// moments, update count), the counters, each environment slot's running episode (to replay it),
// the evaluations so far and, if the run counts it, its coverage (run/coverage.h).
//
// Layout, in the run's output directory:
//   checkpoints/<timesteps>/learner.bin   PpoLearner::SaveState
//   checkpoints/<timesteps>/run.yaml      counters, journals, evaluations, coverage
//   checkpoints/<timesteps>/MANIFEST      sha256 of both, written after them
//   checkpoints/latest                    the newest <timesteps>, written last
// Each file is written atomically (common/atomic_file.h); the newest `keep` checkpoints are
// kept. Thread-compatible.

#include <cstdint>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "actor/evaluation.h"
#include "actor/rollout_collector.h"
#include "run/coverage.h"

namespace dcs::run {

struct RunState {
  int64_t timesteps = 0;  // environment steps collected
  int64_t rollouts = 0;   // rollouts collected (and updates made)
  std::vector<actor::SlotJournal> journals;
  std::vector<double> recent_returns;  // the last finished training episodes' returns
  // Their lengths in environment steps, in the same order; empty in a checkpoint written before
  // DCS kept them (its run's episode length counts only the episodes after it).
  std::vector<int64_t> recent_lengths;
  std::vector<actor::EvaluationResult> evaluations;
  std::vector<ProjectionCounts> coverage;  // empty unless the run counts coverage
};

struct Checkpoint {
  std::string name;  // "<timesteps>"
  RunState state;
  std::string learner;  // PpoLearner::SaveState bytes
};

// The name of the checkpoint at step `timesteps`: fixed width, so names sort as numbers.
std::string CheckpointName(int64_t timesteps);

// The text of run.yaml for `state`, and back. DecodeRunState: DATA_LOSS naming `source` for text
// that does not parse or names an unknown split.
std::string EncodeRunState(const RunState& state);
absl::StatusOr<RunState> DecodeRunState(const std::string& text, const std::string& source);

// The SHA-256 of `bytes` in lower-case hex (as sha256sum prints it; MANIFEST holds these).
std::string Sha256Hex(absl::string_view bytes);

// A checkpoint as it travels between processes: its two files' bytes and the SHA-256 of each,
// computed by the sender.
struct PackedCheckpoint {
  std::string name;
  std::string learner;    // learner.bin
  std::string run_state;  // run.yaml
  std::string learner_sha256;
  std::string run_state_sha256;
};

PackedCheckpoint PackCheckpoint(const Checkpoint& checkpoint);

// The step of checkpoint `packed`, whose files are checked against their SHA-256s but not
// decoded. DATA_LOSS naming the file whose bytes do not match; INVALID_ARGUMENT for a name
// that is not a checkpoint's.
absl::StatusOr<int64_t> CheckPackedCheckpoint(const PackedCheckpoint& packed);

// The checkpoint `packed` holds. Errors as CheckPackedCheckpoint; DATA_LOSS naming the run
// state if it does not parse; INVALID_ARGUMENT for a name other than its step's.
absl::StatusOr<Checkpoint> UnpackCheckpoint(const PackedCheckpoint& packed);

// Writes `state` and `learner` as checkpoint `<state.timesteps>` of `run_dir`, points `latest`
// at it, and deletes all but the newest `keep`. Errors name the file (RESOURCE_EXHAUSTED for a
// full disk); the previous checkpoint stays valid whatever fails.
absl::Status WriteCheckpoint(const std::string& run_dir, const RunState& state,
                             const std::string& learner, int keep);

// The same for a checkpoint as it travelled: its files as they are, named `packed.name`, the
// manifest from its SHA-256s. REQUIRES: CheckPackedCheckpoint(packed) is OK.
absl::Status WritePackedCheckpoint(const std::string& run_dir, const PackedCheckpoint& packed,
                                   int keep);

// The checkpoints of `run_dir` that `latest` vouches for (those newer were being written when
// their writer stopped), oldest first, by name. NOT_FOUND if there is none.
absl::StatusOr<std::vector<std::string>> CheckpointNames(const std::string& run_dir);

// Checkpoint `name` of `run_dir`, read strictly (no fallback to another): NOT_FOUND if there is
// none of that name; DATA_LOSS naming the file that is missing, does not match the MANIFEST or
// does not parse.
absl::StatusOr<Checkpoint> ReadCheckpoint(const std::string& run_dir, const std::string& name);

// The newest checkpoint of `run_dir` that reads back whole: if the one `latest` names is
// corrupt or truncated (checksum, YAML), the next older one. NOT_FOUND if there is none;
// DATA_LOSS if every checkpoint is corrupt.
absl::StatusOr<Checkpoint> ReadLatestCheckpoint(const std::string& run_dir);

}  // namespace dcs::run

#endif  // DCS_RUN_RUN_CHECKPOINT_H_
