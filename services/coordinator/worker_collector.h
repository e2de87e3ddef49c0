// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_WORKER_COLLECTOR_H_
#define DCS_SERVICES_COORDINATOR_WORKER_COLLECTOR_H_

// dcs_workers{role, state}: how many workers the coordinator knows, by role and state, read
// from the registry at each scrape (a worker turns LOST by the passing of time, not by an
// event). Every role and state is reported, zero included. Thread-safe. Borrows the registry,
// which must outlive the collector.

#include <vector>

#include <prometheus/collectable.h>
#include <prometheus/metric_family.h>

#include "coordinator/worker_registry.h"

namespace dcs::services {

class WorkerCollector final : public prometheus::Collectable {
 public:
  explicit WorkerCollector(const coordinator::WorkerRegistry& registry) : registry_(registry) {}
  std::vector<prometheus::MetricFamily> Collect() const override;

 private:
  const coordinator::WorkerRegistry& registry_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_WORKER_COLLECTOR_H_
