// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_RUN_COLLECTOR_H_
#define DCS_SERVICES_RUN_COLLECTOR_H_

// The coordinator's runs, read from the store at each scrape: dcs_runs{state} (every state,
// zeros included) and dcs_queue_depth{queue} (runs waiting for a learner, "runs"; env slots of
// running runs waiting for an actor, "slots"). Thread-safe. Borrows the store, which must
// outlive the collector.

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

#include <vector>

#include "coordinator/run_store.h"

namespace dcs::services {

class RunCollector final : public prometheus::Collectable {
 public:
  explicit RunCollector(coordinator::RunStore& store) : store_(store) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  coordinator::RunStore& store_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_RUN_COLLECTOR_H_
