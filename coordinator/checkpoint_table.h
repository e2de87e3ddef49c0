// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_CHECKPOINT_TABLE_H_
#define DCS_COORDINATOR_CHECKPOINT_TABLE_H_

// The store's index of runs' checkpoints (coordinator/store.h holds the whole store). The
// checkpoints themselves are files beside the store (coordinator/run_files.h), stored durably
// by the caller before it indexes them here.
//
// Thread-safe: every call is one transaction on the store's one connection; it returns after
// the transaction committed. Times are passed in (tests drive the clock).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "coordinator/run_table.h"

namespace dcs::coordinator {

struct CheckpointRecord {
  std::string name;
  int64_t timesteps = 0;
  std::string sha256;  // of the checkpoint's MANIFEST
};

// What evaluations a checkpoint brings (its evaluation log's new part) say of the run, for
// metrics: the latest of them (the highest step) and the best (the highest avg_combined, the
// earliest of equals). A split without contexts has a NaN mean.
struct EvaluationScores {
  int64_t latest_step = 0;
  double latest_avg_combined = 0;
  double latest_id_return = 0;  // the split means of the latest
  double latest_ood_low_return = 0;
  double latest_ood_high_return = 0;
  int64_t best_step = 0;
  double best_avg_combined = 0;
};

class CheckpointTable {
 public:
  CheckpointTable(const CheckpointTable&) = delete;
  CheckpointTable& operator=(const CheckpointTable&) = delete;

  // The learner holding `key` indexes a checkpoint it has stored durably; it becomes the run's
  // latest (RunRecord::checkpoint). `scores`, of the evaluations it brought (none: nullopt),
  // update the run's latest evaluation if they are of a later step and its best if higher, so
  // neither goes back when a learner resumed from an older checkpoint sends evaluations again
  // (StoreCounts reads them). Errors as RunTable::RenewLease.
  absl::Status RecordCheckpoint(const LeaseKey& key, const CheckpointRecord& checkpoint,
                                const std::optional<EvaluationScores>& scores, absl::Time now);
  // A run's checkpoints, oldest first.
  absl::StatusOr<std::vector<CheckpointRecord>> ListCheckpoints(absl::string_view run_id);

 private:
  friend class Store;
  explicit CheckpointTable(internal::StoreConnection& connection) : connection_(connection) {}

  internal::StoreConnection& connection_;  // the Store's, which owns this table too
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_CHECKPOINT_TABLE_H_
