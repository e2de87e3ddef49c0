// Copyright 2026 The DCS Authors.
#include "services/learner/run_metrics.h"

#include <prometheus/registry.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "actor/evaluation.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using ::testing::Pair;
using ::testing::UnorderedElementsAre;

const prometheus::Labels kRun = {
    {"run_id", "run-7"}, {"sweep_id", "sweep-2"}, {"condition", "sinusoidal"}, {"observe", "live"}};

// The series of family `name` in `registry`, each as its labels beyond kRun's, to its value.
std::map<std::map<std::string, std::string>, double> Series(prometheus::Registry& registry,
                                                            const std::string& name) {
  std::map<std::map<std::string, std::string>, double> series;
  for (const prometheus::MetricFamily& family : registry.Collect()) {
    if (family.name != name) continue;
    for (const prometheus::ClientMetric& metric : family.metric) {
      std::map<std::string, std::string> labels;
      for (const prometheus::ClientMetric::Label& label : metric.label) {
        const auto run_label = kRun.find(label.name);
        if (run_label != kRun.end()) {
          EXPECT_EQ(label.value, run_label->second) << name << "'s " << label.name;
        } else {
          labels[label.name] = label.value;
        }
      }
      EXPECT_EQ(labels.size() + kRun.size(), metric.label.size()) << name << " lacks a label";
      series[labels] = family.type == prometheus::MetricType::Counter ? metric.counter.value
                                                                      : metric.gauge.value;
    }
  }
  return series;
}

TEST(RunMetricsTest, LabelsEverySeriesWithTheRunAndRemovesThemWithIt) {
  prometheus::Registry registry;
  auto families = RunMetrics::Register(registry);
  actor::EvaluationResult evaluation;
  evaluation.contexts = {{.context = {.split = actor::Split::kId, .value = 0.5}, .mean = 100},
                         {.context = {.split = actor::Split::kId, .value = 1}, .mean = 200},
                         {.context = {.split = actor::Split::kOodHigh, .value = 2.5}, .mean = 50}};
  evaluation.split_mean[0] = 150;
  evaluation.split_mean[1] = std::nan("");
  evaluation.split_mean[2] = 50;
  {
    RunMetrics metrics(families, kRun);
    EXPECT_THAT(Series(registry, "dcs_env_steps_total"), ElementsAre(Pair(IsEmpty(), 0)));
    learner::TrainingProgress progress{
        .updates = 3, .recent_return = 42, .recent_episode_length = std::nan("")};
    progress.update.approx_kl = 0.01;
    metrics.Update(progress, 256, 4, 0.1);
    // No episode finished yet, and a categorical policy: no length, no std.
    EXPECT_THAT(Series(registry, "dcs_episode_length_mean"), IsEmpty());
    EXPECT_THAT(Series(registry, "dcs_policy_std"), IsEmpty());
    progress.recent_episode_length = 21.5;
    progress.update.learning_rate = 3e-4;
    progress.update.grad_norm = 0.75;
    progress.update.std = 0.9;
    progress.evaluation = &evaluation;
    metrics.Update(progress, 256, 2, 0.1);

    EXPECT_THAT(Series(registry, "dcs_env_steps_total"), ElementsAre(Pair(IsEmpty(), 512)));
    EXPECT_THAT(Series(registry, "dcs_episodes_total"), ElementsAre(Pair(IsEmpty(), 6)));
    EXPECT_THAT(Series(registry, "dcs_episode_return_mean"), ElementsAre(Pair(IsEmpty(), 42)));
    EXPECT_THAT(Series(registry, "dcs_approx_kl"), ElementsAre(Pair(IsEmpty(), 0.01)));
    EXPECT_THAT(Series(registry, "dcs_episode_length_mean"), ElementsAre(Pair(IsEmpty(), 21.5)));
    EXPECT_THAT(Series(registry, "dcs_learning_rate"), ElementsAre(Pair(IsEmpty(), 3e-4)));
    EXPECT_THAT(Series(registry, "dcs_grad_norm"), ElementsAre(Pair(IsEmpty(), 0.75)));
    EXPECT_THAT(Series(registry, "dcs_policy_std"), ElementsAre(Pair(IsEmpty(), 0.9)));
    using Labels = std::map<std::string, std::string>;
    EXPECT_THAT(Series(registry, "dcs_evaluation_return"),
                UnorderedElementsAre(Pair(Labels{{"split", "id"}}, 150),
                                     Pair(Labels{{"split", "ood_low"}}, ::testing::IsNan()),
                                     Pair(Labels{{"split", "ood_high"}}, 50)));
    EXPECT_THAT(Series(registry, "dcs_evaluation_context_return"),
                UnorderedElementsAre(Pair(Labels{{"split", "id"}, {"context", "0.5"}}, 100),
                                     Pair(Labels{{"split", "id"}, {"context", "1"}}, 200),
                                     Pair(Labels{{"split", "ood_high"}, {"context", "2.5"}}, 50)));
  }
  // The run left the learner: none of its series remain.
  for (const prometheus::MetricFamily& family : registry.Collect()) {
    if (family.name == "dcs_learner_update_seconds") continue;  // no run label
    EXPECT_THAT(family.metric, IsEmpty()) << family.name;
  }
}

}  // namespace
}  // namespace dcs::services
