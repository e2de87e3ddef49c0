// Copyright 2026 The DCS Authors.
#include "run/run_plan.h"

#include "env/car_racing.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_spec_yaml.h"

namespace dcs::run {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

RunSpec Spec(absl::string_view yaml) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(yaml, "test.yaml");
  EXPECT_TRUE(spec.ok()) << spec.status();
  return *spec;
}

TEST(RunPlanTest, ResolvesNamesPoolStagesAndEvaluationGrid) {
  const RunSpec spec = Spec(R"(
env: cartpole
seed: 3
total_timesteps: 150000
context: {masspole: 0.2}
feature: length
training_range: [0.35, 0.75]
pool: {size: 5}
stages:
  - {steps: 30000, schedule: {family: constant}}
  - {steps: 30000, schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 100}}
  - {steps: 90000, schedule: {family: cosine_annealing, T_0: 250}}
observe: live
evaluation: {freq: 40000, contexts: {id: [0.5], ood_low: [0.1], ood_high: [1.0, 1.2]}}
)");
  absl::StatusOr<RunPlan> plan = PlanRun(spec, env::CartPole::Features());
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_EQ(plan->feature, env::CartPole::kLength);
  EXPECT_EQ(plan->slot.context[env::CartPole::kMassPole], 0.2);
  ASSERT_EQ(plan->slot.pools.size(), 1u);
  EXPECT_THAT(plan->slot.pools[0].pool.values(), ElementsAre(0.35, 0.45, 0.55, 0.65, 0.75));
  EXPECT_EQ(plan->slot.selection, env::ContextPool::Selection::kRoundRobin);
  ASSERT_EQ(plan->slot.schedules.size(), 1u);
  const auto& stages = plan->slot.schedules[0].stages;
  ASSERT_EQ(stages.size(), 3u);
  EXPECT_EQ(stages[1].steps, 30000);
  EXPECT_EQ(stages[1].spec.min_value, 0.35);
  EXPECT_EQ(stages[1].spec.max_value, 0.75);
  EXPECT_NE(stages[1].spec.seed, stages[2].spec.seed);  // each stage its own stream
  EXPECT_THAT(plan->stage_boundaries, ElementsAre(30000, 60000));
  EXPECT_EQ(plan->slot.observe, env::ObserveMode::kLive);
  EXPECT_THAT(plan->slot.observed_features, ElementsAre(env::CartPole::kLength));
  EXPECT_EQ(plan->slot.run_seed, 3u);
  ASSERT_EQ(plan->evaluation_contexts.size(), 4u);
  EXPECT_EQ(plan->evaluation_contexts[1].split, actor::Split::kOodLow);
  EXPECT_EQ(plan->evaluation_contexts[3].value, 1.2);
  // Multiples of 40000 up to the budget, and the stage boundaries.
  EXPECT_THAT(EvaluationSteps(spec, *plan), ElementsAre(30000, 40000, 60000, 80000, 120000));
}

TEST(RunPlanTest, SingleWholeRunStageAndBlindStaticRuns) {
  RunSpec spec = Spec(R"(
env: cartpole
feature: length
schedule: {family: random_walk}
evaluation: {contexts: {id: [0.5]}}
)");
  absl::StatusOr<RunPlan> plan = PlanRun(spec, env::CartPole::Features());
  ASSERT_TRUE(plan.ok()) << plan.status();
  ASSERT_EQ(plan->slot.schedules.size(), 1u);
  EXPECT_GT(plan->slot.schedules[0].stages[0].steps, int64_t{1} << 62);
  EXPECT_TRUE(plan->stage_boundaries.empty());
  EXPECT_THAT(plan->slot.pools[0].pool.values(), ElementsAre(0.55));  // pool-1: the midpoint

  spec.stages.clear();
  plan = PlanRun(spec, env::CartPole::Features());
  ASSERT_TRUE(plan.ok()) << plan.status();
  EXPECT_TRUE(plan->slot.schedules.empty());
  EXPECT_EQ(plan->slot.observe, env::ObserveMode::kNone);
  EXPECT_TRUE(plan->slot.observed_features.empty());
}

TEST(RunPlanTest, RefusesAnInvalidSpec) {
  RunSpec spec = Spec("env: cartpole\nevaluation: {contexts: {id: [0.5]}}\n");
  spec.ppo.learning_rate = -1;
  const absl::Status status = PlanRun(spec, env::CartPole::Features()).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("ppo.learning_rate"));
}

TEST(RunPlanTest, PolicySpecFollowsTheEnvironment) {
  const PolicySpec cartpole = PolicySpecFor<env::CartPole>(1);
  EXPECT_EQ(cartpole.observation_size, 4);
  EXPECT_EQ(cartpole.num_actions, 2);
  EXPECT_EQ(cartpole.flat_input_size(), 5);
  const PolicySpec car = PolicySpecFor<env::CarRacing>(0);
  EXPECT_TRUE(car.has_image());
  EXPECT_EQ(car.image_channels, 3);
  EXPECT_THAT(car.action_low, ElementsAre(-1, 0, 0));
  EXPECT_THAT(car.action_high, ElementsAre(1, 1, 1));
}

}  // namespace
}  // namespace dcs::run
