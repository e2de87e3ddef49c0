// Copyright 2026 The DCS Authors.
#include "services/coordinator/run_collector.h"

#include <cmath>
#include <string>
#include <utility>

#include "actor/split.h"
#include "common/enum_names.h"
#include "coordinator/run_files.h"
#include "services/log.h"

namespace dcs::services {
namespace {

using Labels = std::vector<prometheus::ClientMetric::Label>;

prometheus::ClientMetric Gauge(Labels labels, double number) {
  prometheus::ClientMetric metric;
  metric.label = std::move(labels);
  metric.gauge.value = number;
  return metric;
}

prometheus::MetricFamily GaugeFamily(std::string name, std::string help,
                                     std::vector<prometheus::ClientMetric> metrics = {}) {
  return {std::move(name), std::move(help), prometheus::MetricType::Gauge, std::move(metrics)};
}

prometheus::ClientMetric::Label StateLabel(coordinator::RunState state) {
  return {"state", std::string(NameOf(coordinator::kRunStateNames, state))};
}

// `labels` with `extra` added.
Labels With(Labels labels, prometheus::ClientMetric::Label extra) {
  labels.push_back(std::move(extra));
  return labels;
}

// The per-run families, filled run by run.
struct RunFamilies {
  prometheus::MetricFamily step = GaugeFamily(
      "dcs_run_step",
      "The furthest environment step the run's learners reached: it never goes down, not even "
      "when a learner resumes the run from an older checkpoint.");
  prometheus::MetricFamily total = GaugeFamily("dcs_run_total_timesteps",
                                               "The run's total_timesteps.");
  prometheus::MetricFamily avg_combined = GaugeFamily(
      "dcs_run_evaluation_avg_combined",
      "avg_combined (the mean over every evaluation context) of the run's latest "
      "(which=\"latest\") and best (\"best\") evaluation stored with its checkpoints.");
  prometheus::MetricFamily evaluation_step = GaugeFamily(
      "dcs_run_evaluation_step",
      "The environment step of the run's latest and best evaluation (which).");
  prometheus::MetricFamily split_return = GaugeFamily(
      "dcs_run_evaluation_return",
      "The mean return of each split (id, ood_low, ood_high) in the run's latest evaluation.");
  prometheus::MetricFamily checkpoint_age = GaugeFamily(
      "dcs_run_checkpoint_age_seconds",
      "Seconds since a running run's latest checkpoint (since its lease began before its "
      "first).");

  void Add(const coordinator::LiveRun& run, absl::Time now) {
    const Labels labels = {{"run_id", run.run_id},
                           {"sweep_id", run.sweep_id},
                           {"condition", run.condition},
                           {"observe", run.observe}};
    step.metric.push_back(Gauge(labels, static_cast<double>(run.timesteps)));
    total.metric.push_back(Gauge(labels, static_cast<double>(run.total_timesteps)));
    if (run.scores.has_value()) {
      const coordinator::EvaluationScores& scores = *run.scores;
      AddScore(labels, "latest", scores.latest_avg_combined, scores.latest_step);
      AddScore(labels, "best", scores.best_avg_combined, scores.best_step);
      for (const auto& [split, mean] :
           {std::pair(actor::Split::kId, scores.latest_id_return),
            std::pair(actor::Split::kOodLow, scores.latest_ood_low_return),
            std::pair(actor::Split::kOodHigh, scores.latest_ood_high_return)}) {
        if (std::isnan(mean)) continue;  // a split without contexts
        split_return.metric.push_back(
            Gauge(With(labels, {"split", std::string(NameOf(actor::kSplitNames, split))}), mean));
      }
    }
    if (run.checkpointed_at.has_value()) {
      checkpoint_age.metric.push_back(
          Gauge(labels, absl::ToDoubleSeconds(now - *run.checkpointed_at)));
    }
  }

  // An evaluation's score and step, unless it has none (NaN).
  void AddScore(const Labels& labels, const std::string& which, double score, int64_t at) {
    if (std::isnan(score)) return;
    avg_combined.metric.push_back(Gauge(With(labels, {"which", which}), score));
    evaluation_step.metric.push_back(
        Gauge(With(labels, {"which", which}), static_cast<double>(at)));
  }
};

}  // namespace

std::vector<prometheus::MetricFamily> RunCollector::Collect() const {
  const absl::Time now = now_();
  absl::StatusOr<coordinator::StoreCounts> counts = store_.Counts();
  if (!counts.ok()) {
    // The scrape shows the series missing (an alert's `absent`); the log says why.
    Log(LogLevel::kError, "cannot count the store's runs for /metrics",
        {{"error", counts.status().ToString()}});
    return {};
  }
  std::vector<prometheus::MetricFamily> families;
  prometheus::MetricFamily& runs =
      families.emplace_back(GaugeFamily("dcs_runs", "Runs the coordinator knows, by state."));
  for (const auto& [state, count] : counts->runs_by_state) {
    runs.metric.push_back(Gauge({StateLabel(state)}, static_cast<double>(count)));
  }
  families.push_back(GaugeFamily(
      "dcs_queue_depth",
      "Work waiting: runs for a learner (queue=\"runs\"), env slots and evaluation jobs for "
      "an actor (\"slots\", \"evaluations\").",
      {Gauge({{"queue", "runs"}}, static_cast<double>(counts->free_learner_leases)),
       Gauge({{"queue", "slots"}}, static_cast<double>(counts->free_slot_leases)),
       Gauge({{"queue", "evaluations"}}, static_cast<double>(counts->free_evaluation_jobs))}));
  families.push_back(GaugeFamily(
      "dcs_evaluation_oldest_pending_seconds",
      "Seconds since the evaluation of the oldest job waiting for an actor was submitted; 0 if "
      "none waits.",
      {Gauge({}, counts->oldest_free_evaluation.has_value()
                     ? absl::ToDoubleSeconds(now - *counts->oldest_free_evaluation)
                     : 0)}));

  RunFamilies per_run;
  for (const coordinator::LiveRun& run : counts->live_runs) per_run.Add(run, now);
  for (prometheus::MetricFamily* family :
       {&per_run.step, &per_run.total, &per_run.avg_combined, &per_run.evaluation_step,
        &per_run.split_return, &per_run.checkpoint_age}) {
    families.push_back(std::move(*family));
  }

  prometheus::MetricFamily sweep_runs = GaugeFamily(
      "dcs_sweep_runs",
      "Runs of each sweep with work ahead or among the 20 most recent, by state.");
  prometheus::MetricFamily steps_remaining = GaugeFamily(
      "dcs_sweep_steps_remaining",
      "Environment steps the queued and running runs of each sweep shown have left (a study's "
      "trials not yet asked are not counted).");
  prometheus::MetricFamily best = GaugeFamily(
      "dcs_sweep_best_avg_combined",
      "Each sweep's best trial so far, as `dcs watch` names it (condition, observe), and its "
      "IQM over seeds of its completed runs' last avg_combined.");
  for (const coordinator::SweepCounts& sweep : counts->sweeps) {
    const prometheus::ClientMetric::Label sweep_label = {"sweep_id", sweep.sweep_id};
    for (const auto& [state, count] : sweep.runs_by_state) {
      sweep_runs.metric.push_back(
          Gauge({sweep_label, StateLabel(state)}, static_cast<double>(count)));
    }
    steps_remaining.metric.push_back(
        Gauge({sweep_label}, static_cast<double>(sweep.steps_remaining)));
    if (sweep.best.has_value()) {
      best.metric.push_back(Gauge({sweep_label,
                                   {"condition", sweep.best->condition},
                                   {"observe", sweep.best->observe}},
                                  sweep.best->score));
    }
  }
  families.push_back(std::move(sweep_runs));
  families.push_back(std::move(steps_remaining));
  families.push_back(std::move(best));

  families.push_back(GaugeFamily(
      "dcs_store_bytes", "Bytes of the coordinator's store on disk (database and its WAL).",
      {Gauge({}, static_cast<double>(counts->store_bytes))}));
  const absl::StatusOr<coordinator::DiskSpace> space = coordinator::DiskSpaceOf(data_dir_);
  if (!space.ok()) {
    Log(LogLevel::kError, "cannot measure the data directory for /metrics",
        {{"error", space.status().ToString()}});
    return families;
  }
  families.push_back(GaugeFamily(
      "dcs_data_dir_free_bytes",
      "Bytes free for the coordinator on the file system of its data directory.",
      {Gauge({}, static_cast<double>(space->free_bytes))}));
  families.push_back(GaugeFamily("dcs_data_dir_capacity_bytes",
                                 "Size in bytes of the file system of its data directory.",
                                 {Gauge({}, static_cast<double>(space->capacity_bytes))}));
  return families;
}

}  // namespace dcs::services
