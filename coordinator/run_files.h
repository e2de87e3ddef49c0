// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_FILES_H_
#define DCS_COORDINATOR_RUN_FILES_H_

// What the coordinator keeps of each run on disk, in its data directory: the run's directory,
// <data_dir>/runs/<run id>/, laid out as `dcs train --out` lays one out (run/run_directory.h):
// the config, the checkpoints learners send, the evaluation log; the log appended to at each
// checkpoint (run/appended_evaluation_log.h). So a learner's disk holds nothing that matters,
// and `dcs runs get` hands users the same files `dcs train` writes.
// Thread-compatible (one writer per run: its learner lease holder).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "coordinator/checkpoint_table.h"
#include "dcs/v1/evaluation.pb.h"
#include "run/run_checkpoint.h"
#include "run/run_directory.h"

namespace dcs::coordinator {

struct RunFile {
  std::string path;  // relative to the run's directory
  std::string contents;
};

// <data_dir>/runs/<run_id>.
std::string RunDirectory(absl::string_view data_dir, absl::string_view run_id);

// Checks `checkpoint` (errors as run::CheckPackedCheckpoint), then stores it in `run_dir`
// as run::WritePackedCheckpoint does, keeping the newest `keep`, after appending `log_since`,
// the run's evaluation log from evaluation `first_evaluation` on, as run::AppendEvaluationLog
// does (errors as it). The log goes first, so it always holds every evaluation of the newest
// checkpoint, which a learner resumes from. Nothing is stored unless all of it checks. Returns
// its index entry (the SHA-256 is learner.bin's). A full disk is UNAVAILABLE, not
// RESOURCE_EXHAUSTED: the learner may send the same checkpoint again once there is room, as
// after a full store (coordinator/store.h).
absl::StatusOr<CheckpointRecord> StoreCheckpoint(const std::string& run_dir,
                                                 const run::PackedCheckpoint& checkpoint,
                                                 int64_t first_evaluation,
                                                 const v1::EvaluationLog& log_since, int keep);

// The scores of `log`'s evaluations (a checkpoint's new part: StoreCheckpoint's `log_since`) as
// CheckpointTable::RecordCheckpoint records them; nullopt if it holds none.
std::optional<EvaluationScores> ScoreEvaluations(const v1::EvaluationLog& log);

// The newest readable checkpoint of `run_dir` as a learner receives it. Errors as
// run::ReadLatestCheckpoint (NOT_FOUND when there is none yet).
absl::StatusOr<run::PackedCheckpoint> LatestCheckpoint(const std::string& run_dir);

// The file system holding `data_dir`, as statvfs(3) sees it: bytes free for an unprivileged
// user (what the coordinator, not running as root, may still write) and its size.
struct DiskSpace {
  int64_t free_bytes = 0;
  int64_t capacity_bytes = 0;
};
// An error naming `data_dir` if it cannot be read.
absl::StatusOr<DiskSpace> DiskSpaceOf(const std::string& data_dir);

// Every file under `run_dir`, by path, as `dcs train` would have left them: the appended
// evaluation log as evaluations.csv and .json (run::EvaluationLogFiles). NOT_FOUND if there is
// no such directory; DATA_LOSS as run::ReadEvaluationLog.
absl::StatusOr<std::vector<RunFile>> ReadRunFiles(const std::string& run_dir);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_FILES_H_
