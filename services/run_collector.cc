// Copyright 2026 The DCS Authors.
#include "services/run_collector.h"

#include <string>
#include <utility>

namespace dcs::services {
namespace {

prometheus::ClientMetric Gauge(std::string label, std::string value, double number) {
  prometheus::ClientMetric metric;
  metric.label = {{std::move(label), std::move(value)}};
  metric.gauge.value = number;
  return metric;
}

}  // namespace

std::vector<prometheus::MetricFamily> RunCollector::Collect() const {
  absl::StatusOr<coordinator::StoreCounts> counts = store_.Counts();
  if (!counts.ok()) return {};  // the scrape shows the series missing; the logs say why
  prometheus::MetricFamily runs{"dcs_runs", "Runs the coordinator knows, by state.",
                                prometheus::MetricType::Gauge, {}};
  for (const auto& [state, count] : counts->runs_by_state) {
    runs.metric.push_back(Gauge("state", std::string(NameOf(coordinator::kRunStateNames, state)),
                                static_cast<double>(count)));
  }
  prometheus::MetricFamily queues{
      "dcs_queue_depth",
      "Work waiting: runs for a learner (queue=\"runs\"), env slots and evaluation jobs for "
      "an actor (\"slots\", \"evaluations\").",
      prometheus::MetricType::Gauge,
      {Gauge("queue", "runs", static_cast<double>(counts->free_learner_leases)),
       Gauge("queue", "slots", static_cast<double>(counts->free_slot_leases)),
       Gauge("queue", "evaluations", static_cast<double>(counts->free_evaluation_jobs))}};
  return {std::move(runs), std::move(queues)};
}

}  // namespace dcs::services
