// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_STUDY_SWEEP_DRIVER_H_
#define DCS_COORDINATOR_STUDY_SWEEP_DRIVER_H_

// Drives every open study sweep of the store: each tick steps each one once
// (coordinator/study_sweep.h: asks for trials while fewer than `parallel` train and the budget
// allows, tells those whose runs ended, retrains the best, closes the sweep). Keeps each open
// sweep's spec as a value: the one read at submission, handed over (Adopt), or else read once
// from the spec text the store keeps (after a restart); dropped when the sweep closes. Driven by
// its caller's clock (Tick): the coordinator ticks it about once a second, a test when it
// chooses. Thread-safe: Adopt may come from any thread; Tick from one thread at a time. Borrows
// the store and the logs, which must outlive it.

#include <map>
#include <string>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/statusor.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep.h"
#include "coordinator/study_sweep_spec.h"
#include "coordinator/sweep_results.h"

namespace dcs::coordinator {

class StudySweepDriver {
 public:
  // Steps the study sweeps of `store`, whose runs' directories are in `data_dir` and whose
  // completed runs' logs `logs` reads.
  StudySweepDriver(Store& store, std::string data_dir, CompletedRunLogs& logs);

  StudySweepDriver(const StudySweepDriver&) = delete;
  StudySweepDriver& operator=(const StudySweepDriver&) = delete;

  // Keeps `spec`, read when the sweep `sweep_id` was submitted, as its spec, so that the spec
  // text is not read again. A sweep whose spec is kept already keeps it.
  void Adopt(const std::string& sweep_id, StudySweepSpec spec);

  // What a tick did to one open study sweep: its step, or why it could not step (its spec text
  // does not read, the store failed). A sweep that could not step is tried at the next tick.
  struct SweepTick {
    std::string sweep_id;
    absl::StatusOr<StudySweepStep> step;
  };
  // One step of each open study sweep, at `now`. Errors: the store's, listing the open sweeps.
  absl::StatusOr<std::vector<SweepTick>> Tick(absl::Time now);

 private:
  // The kept spec of `sweep`, read from its text if none is kept.
  absl::StatusOr<const StudySweepSpec*> SpecOf(const SweepRecord& sweep);

  Store& store_;
  const std::string data_dir_;
  CompletedRunLogs& logs_;
  absl::Mutex mu_;
  // By sweep id. A map, so that a spec Tick steps stays where it is while Adopt adds another;
  // only Tick removes one.
  std::map<std::string, StudySweepSpec> specs_ ABSL_GUARDED_BY(mu_);
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_STUDY_SWEEP_DRIVER_H_
