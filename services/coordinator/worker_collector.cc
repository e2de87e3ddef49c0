// Copyright 2026 The DCS Authors.
#include "services/coordinator/worker_collector.h"

#include <string>

#include "absl/time/clock.h"

namespace dcs::services {

std::vector<prometheus::MetricFamily> WorkerCollector::Collect() const {
  using coordinator::WorkerState;
  prometheus::MetricFamily family{"dcs_workers",
                                  "Workers known to the coordinator, by role and state.",
                                  prometheus::MetricType::Gauge,
                                  {}};
  const std::vector<coordinator::WorkerRecord> workers = registry_.List(absl::Now());
  for (WorkerRole role : {WorkerRole::kLearner, WorkerRole::kActor}) {
    for (WorkerState state : {WorkerState::kAlive, WorkerState::kLost}) {
      prometheus::ClientMetric metric;
      metric.label = {{"role", std::string(WorkerRoleName(role))},
                      {"state", std::string(coordinator::WorkerStateName(state))}};
      for (const coordinator::WorkerRecord& worker : workers) {
        if (worker.info.role == role && worker.state == state) metric.gauge.value += 1;
      }
      family.metric.push_back(std::move(metric));
    }
  }
  return {family};
}

}  // namespace dcs::services
