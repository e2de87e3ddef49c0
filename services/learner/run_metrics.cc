// Copyright 2026 The DCS Authors.
#include "services/learner/run_metrics.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "absl/strings/str_format.h"
#include "actor/split.h"
#include "common/enum_names.h"

namespace dcs::services {

struct RunMetrics::Families {
  explicit Families(prometheus::Registry& registry)
      : env_steps(Counter(registry, "dcs_env_steps_total",
                          "Environment steps learnt from, per run.")),
        episodes(Counter(registry, "dcs_episodes_total",
                         "Training episodes finished, per run.")),
        episode_return(Gauge(registry, "dcs_episode_return_mean",
                             "Mean return of the last 100 training episodes, per run.")),
        episode_length(Gauge(registry, "dcs_episode_length_mean",
                             "Mean length in environment steps of the last 100 training "
                             "episodes, per run (SB3's ep_len_mean).")),
        steps_per_second(Gauge(registry, "dcs_steps_per_second",
                               "Environment steps per second since the run came to this "
                               "learner, updates included.")),
        policy_version(Gauge(registry, "dcs_policy_version",
                             "The run's policy version (PPO updates so far).")),
        policy_loss(Gauge(registry, "dcs_policy_loss", "Policy-gradient loss of the last update.")),
        value_loss(Gauge(registry, "dcs_value_loss", "Value loss of the last update.")),
        entropy_loss(Gauge(registry, "dcs_entropy_loss", "Entropy loss of the last update.")),
        approx_kl(Gauge(registry, "dcs_approx_kl",
                        "Approximate KL divergence of the last update.")),
        clip_fraction(Gauge(registry, "dcs_clip_fraction",
                            "Fraction of clipped ratios in the last update.")),
        explained_variance(Gauge(registry, "dcs_explained_variance",
                                 "Explained variance of the value function, last update.")),
        learning_rate(Gauge(registry, "dcs_learning_rate", "Learning rate of the last update.")),
        policy_std(Gauge(registry, "dcs_policy_std",
                         "A Gaussian policy's mean standard deviation after the last update "
                         "(no series for a categorical policy).")),
        grad_norm(Gauge(registry, "dcs_grad_norm",
                        "The gradient's norm before clipping, mean over the last update's "
                        "gradient steps.")),
        evaluation_return(Gauge(registry, "dcs_evaluation_return",
                                "Mean evaluation return of the latest evaluation, per run and "
                                "split.")),
        evaluation_context_return(Gauge(registry, "dcs_evaluation_context_return",
                                        "Mean evaluation return of the latest evaluation, per "
                                        "run, split and context (the varied feature's value).")),
        update_seconds(prometheus::BuildHistogram()
                           .Name("dcs_learner_update_seconds")
                           .Help("Wall seconds of one PPO update (with evaluations due).")
                           .Register(registry)) {}

  static prometheus::Family<prometheus::Counter>& Counter(prometheus::Registry& registry,
                                                          const char* name, const char* help) {
    return prometheus::BuildCounter().Name(name).Help(help).Register(registry);
  }
  static prometheus::Family<prometheus::Gauge>& Gauge(prometheus::Registry& registry,
                                                      const char* name, const char* help) {
    return prometheus::BuildGauge().Name(name).Help(help).Register(registry);
  }

  prometheus::Family<prometheus::Counter>& env_steps;
  prometheus::Family<prometheus::Counter>& episodes;
  prometheus::Family<prometheus::Gauge>& episode_return;
  prometheus::Family<prometheus::Gauge>& episode_length;
  prometheus::Family<prometheus::Gauge>& steps_per_second;
  prometheus::Family<prometheus::Gauge>& policy_version;
  prometheus::Family<prometheus::Gauge>& policy_loss;
  prometheus::Family<prometheus::Gauge>& value_loss;
  prometheus::Family<prometheus::Gauge>& entropy_loss;
  prometheus::Family<prometheus::Gauge>& approx_kl;
  prometheus::Family<prometheus::Gauge>& clip_fraction;
  prometheus::Family<prometheus::Gauge>& explained_variance;
  prometheus::Family<prometheus::Gauge>& learning_rate;
  prometheus::Family<prometheus::Gauge>& policy_std;
  prometheus::Family<prometheus::Gauge>& grad_norm;
  prometheus::Family<prometheus::Gauge>& evaluation_return;
  prometheus::Family<prometheus::Gauge>& evaluation_context_return;
  prometheus::Family<prometheus::Histogram>& update_seconds;
  prometheus::Histogram& update_histogram =
      update_seconds.Add({}, prometheus::Histogram::BucketBoundaries{
                                 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10, 30, 60});
};

std::shared_ptr<RunMetrics::Families> RunMetrics::Register(prometheus::Registry& registry) {
  return std::make_shared<Families>(registry);
}

RunMetrics::RunMetrics(std::shared_ptr<Families> families, prometheus::Labels labels)
    : families_(std::move(families)), labels_(std::move(labels)) {
  // Known series start at zero.
  families_->env_steps.Add(labels_);
  families_->episodes.Add(labels_);
}

RunMetrics::~RunMetrics() {
  families_->env_steps.Remove(&families_->env_steps.Add(labels_));
  families_->episodes.Remove(&families_->episodes.Add(labels_));
  for (prometheus::Family<prometheus::Gauge>* family :
       {&families_->episode_return, &families_->episode_length, &families_->steps_per_second,
        &families_->policy_version, &families_->policy_loss, &families_->value_loss,
        &families_->entropy_loss, &families_->approx_kl, &families_->clip_fraction,
        &families_->explained_variance, &families_->learning_rate, &families_->policy_std,
        &families_->grad_norm}) {
    family->Remove(&family->Add(labels_));
  }
  for (const auto& [split, name] : actor::kSplitNames) {
    families_->evaluation_return.Remove(
        &families_->evaluation_return.Add(With({{"split", std::string(name)}})));
  }
  for (const prometheus::Labels& labels : context_labels_) {
    families_->evaluation_context_return.Remove(
        &families_->evaluation_context_return.Add(labels));
  }
}

prometheus::Labels RunMetrics::With(
    std::initializer_list<prometheus::Labels::value_type> extra) const {
  prometheus::Labels labels = labels_;
  labels.insert(extra);
  return labels;
}

void RunMetrics::Update(const learner::TrainingProgress& progress, int64_t steps,
                        int64_t episodes, double seconds) {
  families_->env_steps.Add(labels_).Increment(static_cast<double>(steps));
  families_->episodes.Add(labels_).Increment(static_cast<double>(episodes));
  if (!std::isnan(progress.recent_return)) {
    families_->episode_return.Add(labels_).Set(progress.recent_return);
  }
  if (!std::isnan(progress.recent_episode_length)) {
    families_->episode_length.Add(labels_).Set(progress.recent_episode_length);
  }
  families_->steps_per_second.Add(labels_).Set(progress.steps_per_second);
  families_->policy_version.Add(labels_).Set(static_cast<double>(progress.updates));
  families_->policy_loss.Add(labels_).Set(progress.update.policy_loss);
  families_->value_loss.Add(labels_).Set(progress.update.value_loss);
  families_->entropy_loss.Add(labels_).Set(progress.update.entropy_loss);
  families_->approx_kl.Add(labels_).Set(progress.update.approx_kl);
  families_->clip_fraction.Add(labels_).Set(progress.update.clip_fraction);
  families_->explained_variance.Add(labels_).Set(progress.update.explained_variance);
  families_->learning_rate.Add(labels_).Set(progress.update.learning_rate);
  if (progress.update.std.has_value()) {
    families_->policy_std.Add(labels_).Set(*progress.update.std);
  }
  families_->grad_norm.Add(labels_).Set(progress.update.grad_norm);
  if (progress.evaluation != nullptr) {
    for (const auto& [split, name] : actor::kSplitNames) {
      families_->evaluation_return.Add(With({{"split", std::string(name)}}))
          .Set(progress.evaluation->split_mean[static_cast<int>(split)]);
    }
    for (const actor::ContextResult& context : progress.evaluation->contexts) {
      prometheus::Labels labels =
          With({{"split", std::string(NameOf(actor::kSplitNames, context.context.split))},
                {"context", absl::StrFormat("%g", context.context.value)}});
      families_->evaluation_context_return.Add(labels).Set(context.mean);
      if (std::find(context_labels_.begin(), context_labels_.end(), labels) ==
          context_labels_.end()) {
        context_labels_.push_back(std::move(labels));
      }
    }
  }
  families_->update_histogram.Observe(seconds);
}

}  // namespace dcs::services
