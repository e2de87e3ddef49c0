// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_
#define DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_

// The coordinator's runs, read from the store at each scrape (Store::Counts: one transaction,
// one query per kind of series), so that they survive learner handovers and restarts:
//   dcs_runs{state}                       every state, zeros included
//   dcs_queue_depth{queue}                runs waiting for a learner ("runs"); env slots and
//                                         evaluation jobs waiting for an actor ("slots",
//                                         "evaluations")
//   dcs_evaluation_oldest_pending_seconds since the oldest waiting evaluation job's evaluation
//                                         was submitted (0 if none waits)
// Per run queued or running (labels run_id, sweep_id, condition, observe; gone once it ends):
//   dcs_run_step                          the furthest step its learners reached (monotone)
//   dcs_run_total_timesteps
//   dcs_run_evaluation_avg_combined{which="latest"|"best"}, dcs_run_evaluation_step{which}
//                                         its latest and best evaluation, and their steps
//   dcs_run_evaluation_return{split}      the latest evaluation's split means
//   dcs_run_checkpoint_age_seconds        running runs: since its latest checkpoint, or since
//                                         its lease began before the first
// Per sweep with work ahead (runs queued or running, or a study adding trials) and per sweep
// among the 20 most recent by id (coordinator::kRecentSweeps), so that a sweep's tally and best
// trial outlive it while series stay bounded:
//   dcs_sweep_runs{sweep_id, state}, dcs_sweep_steps_remaining{sweep_id}
//   dcs_sweep_best_avg_combined{sweep_id, condition, observe}   its best trial as `dcs watch`
//                                         names it, and that trial's IQM
// The data directory: dcs_store_bytes (coordinator.db and its WAL), dcs_data_dir_free_bytes,
// dcs_data_dir_capacity_bytes.
// Series: 10 per run queued or running, 7 per sweep shown, and a dozen. A dashboard's ETA is the
// steps remaining over the sweep's summed dcs_env_steps_total rate.
// Thread-safe. Borrows the store, which must outlive the collector.

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

#include <string>
#include <vector>

#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/store.h"

namespace dcs::services {

class RunCollector final : public prometheus::Collectable {
 public:
  // `data_dir`: the coordinator's, which holds the store. `now`: the clock ages are read by.
  RunCollector(coordinator::Store& store, std::string data_dir,
               absl::Time (*now)() = &absl::Now)
      : store_(store), data_dir_(std::move(data_dir)), now_(now) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  coordinator::Store& store_;
  const std::string data_dir_;
  absl::Time (*const now_)();
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_
