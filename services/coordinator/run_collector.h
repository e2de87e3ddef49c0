// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_
#define DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_

// The coordinator's runs, read from the store at each scrape:
//   dcs_runs{state}                       every state, zeros included
//   dcs_queue_depth{queue}                runs waiting for a learner ("runs"); env slots and
//                                         evaluation jobs waiting for an actor ("slots",
//                                         "evaluations")
//   dcs_sweep_runs{sweep_id, state}       per sweep with work ahead (runs queued or running,
//   dcs_sweep_steps_remaining{sweep_id}   or a study adding trials), so series stay bounded;
//                                         a finished sweep's series go stale
// A dashboard's ETA is the steps remaining over the sweep's summed dcs_env_steps_total rate.
// Thread-safe. Borrows the store, which must outlive the collector.

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

#include <vector>

#include "coordinator/store.h"

namespace dcs::services {

class RunCollector final : public prometheus::Collectable {
 public:
  explicit RunCollector(coordinator::Store& store) : store_(store) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  coordinator::Store& store_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_RUN_COLLECTOR_H_
