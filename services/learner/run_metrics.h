// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_LEARNER_RUN_METRICS_H_
#define DCS_SERVICES_LEARNER_RUN_METRICS_H_

// A learner's training metrics, one series per hosted run (bounded by --max-runs; a run's
// series are removed when it leaves the learner), labelled with the run's run_id, sweep_id,
// condition and observe (the last three empty for a run alone), so that dashboards filter by
// sweep and condition. Names and labels: docs/monitoring.md. Thread-compatible: the
// run's thread updates it while scrapes read its series (prometheus-cpp metrics allow that).
//
//   dcs_env_steps_total, dcs_episodes_total          counters
//   dcs_episode_return_mean, dcs_episode_length_mean the last 100 training episodes
//   dcs_steps_per_second, dcs_policy_version
//   dcs_policy_loss, dcs_value_loss, dcs_entropy_loss, dcs_approx_kl, dcs_clip_fraction,
//   dcs_explained_variance, dcs_learning_rate, dcs_grad_norm (before clipping),
//   dcs_policy_std (a Gaussian policy's only)       of the latest update
//   dcs_evaluation_return{split}                     the latest evaluation's split means
//   dcs_evaluation_context_return{split, context}    its per-context means (context: the
//                                                    varied feature's value)
//   dcs_learner_update_seconds                       histogram, no run label

#include <prometheus/counter.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include <initializer_list>
#include <memory>
#include <vector>

#include "learner/training_run.h"

namespace dcs::services {

class RunMetrics {
 public:
  // The families, registered in `registry` (which must outlive them); once per registry.
  struct Families;
  static std::shared_ptr<Families> Register(prometheus::Registry& registry);

  // Series for the run labelled `labels` (run_id, sweep_id, condition, observe).
  RunMetrics(std::shared_ptr<Families> families, prometheus::Labels labels);
  ~RunMetrics();  // removes the run's series
  RunMetrics(const RunMetrics&) = delete;
  RunMetrics& operator=(const RunMetrics&) = delete;

  // After an update that took `seconds`, having finished `episodes` training episodes.
  void Update(const learner::TrainingProgress& progress, int64_t steps, int64_t episodes,
              double seconds);

 private:
  // `labels_` with `extra` added.
  prometheus::Labels With(std::initializer_list<prometheus::Labels::value_type> extra) const;

  const std::shared_ptr<Families> families_;
  const prometheus::Labels labels_;
  // The per-context series set so far (their labels), removed with the run's.
  std::vector<prometheus::Labels> context_labels_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_LEARNER_RUN_METRICS_H_
