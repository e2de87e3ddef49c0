// Copyright 2026 The DCS Authors.
#include "services/coordinator/run_collector.h"

#include <string>
#include <utility>

#include "services/log.h"

namespace dcs::services {
namespace {

prometheus::ClientMetric Gauge(prometheus::ClientMetric::Label label, double number) {
  prometheus::ClientMetric metric;
  metric.label = {std::move(label)};
  metric.gauge.value = number;
  return metric;
}

prometheus::ClientMetric::Label StateLabel(coordinator::RunState state) {
  return {"state", std::string(NameOf(coordinator::kRunStateNames, state))};
}

}  // namespace

std::vector<prometheus::MetricFamily> RunCollector::Collect() const {
  absl::StatusOr<coordinator::StoreCounts> counts = store_.Counts();
  if (!counts.ok()) {
    // The scrape shows the series missing (an alert's `absent`); the log says why.
    Log(LogLevel::kError, "cannot count the store's runs for /metrics",
        {{"error", counts.status().ToString()}});
    return {};
  }
  prometheus::MetricFamily runs{"dcs_runs", "Runs the coordinator knows, by state.",
                                prometheus::MetricType::Gauge, {}};
  for (const auto& [state, count] : counts->runs_by_state) {
    runs.metric.push_back(Gauge(StateLabel(state), static_cast<double>(count)));
  }
  prometheus::MetricFamily queues{
      "dcs_queue_depth",
      "Work waiting: runs for a learner (queue=\"runs\"), env slots and evaluation jobs for "
      "an actor (\"slots\", \"evaluations\").",
      prometheus::MetricType::Gauge,
      {Gauge({"queue", "runs"}, static_cast<double>(counts->free_learner_leases)),
       Gauge({"queue", "slots"}, static_cast<double>(counts->free_slot_leases)),
       Gauge({"queue", "evaluations"}, static_cast<double>(counts->free_evaluation_jobs))}};
  prometheus::MetricFamily sweep_runs{
      "dcs_sweep_runs", "Runs of each sweep with work ahead, by state.",
      prometheus::MetricType::Gauge, {}};
  prometheus::MetricFamily steps_remaining{
      "dcs_sweep_steps_remaining",
      "Environment steps the queued and running runs of each sweep with work ahead have left "
      "(a study's trials not yet asked are not counted).",
      prometheus::MetricType::Gauge,
      {}};
  for (const coordinator::ActiveSweepCounts& sweep : counts->active_sweeps) {
    for (const auto& [state, count] : sweep.runs_by_state) {
      prometheus::ClientMetric metric = Gauge(StateLabel(state), static_cast<double>(count));
      metric.label.insert(metric.label.begin(), {"sweep_id", sweep.sweep_id});
      sweep_runs.metric.push_back(std::move(metric));
    }
    steps_remaining.metric.push_back(
        Gauge({"sweep_id", sweep.sweep_id}, static_cast<double>(sweep.steps_remaining)));
  }
  return {std::move(runs), std::move(queues), std::move(sweep_runs), std::move(steps_remaining)};
}

}  // namespace dcs::services
