// Copyright 2026 The DCS Authors.
//
// RolloutCollector (actor/rollout_collector.h) over a run's slots stepped apart: each slot in a
// VectorEnv of its own with the run's run_slots, collected by its own collector, gives parts
// that merge (actor/slot_rollout.h) into exactly the rollouts, finished episodes and journals
// of one collector over all the slots; and a slot rebuilt from its journal mid-run continues
// exactly.

#include "actor/rollout_collector.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "absl/status/statusor.h"
#include "actor/policy_network.h"
#include "actor/rollout.h"
#include "actor/slot_rollout.h"
#include "common/random.h"
#include "env/cartpole.h"
#include "env/vector_env.h"
#include "gtest/gtest.h"
#include "run/run_plan.h"
#include "run/run_spec.h"
#include "run/run_spec_yaml.h"

namespace dcs::actor {
namespace {

using Vec = env::VectorEnv<env::CartPole>;
using Collector = RolloutCollector<env::CartPole>;

constexpr int kSlots = 3;
constexpr int kSteps = 64;
constexpr int kRollouts = 16;  // 1024 steps per slot: past the time limit of 500

// kRollouts rollouts of kSteps steps of kSlots slots; the stage boundary at 1000 falls inside
// rollout 5 (steps 960 to 1151), so slots reset on both sides of it within one rollout.
constexpr char kRun[] = R"(
env: cartpole
seed: 11
total_timesteps: 3072
n_envs: 3
feature: length
training_range: [0.35, 0.75]
pool: {size: 3}
stages:
  - {steps: 1000, schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}}
  - {steps: 2072, schedule: {family: random_walk, std_frac: 0.05}}
observe: live
evaluation: {freq: 1024, episodes: 2, contexts: {id: [0.5]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)";

run::RunPlan Plan() {
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(kRun, "test.yaml");
  EXPECT_TRUE(spec.ok()) << spec.status();
  absl::StatusOr<run::RunPlan> plan = run::PlanRun(spec.value(), env::CartPole::Features());
  EXPECT_TRUE(plan.ok()) << plan.status();
  return plan.value();
}

// A CartPole policy that samples: its first hidden unit balances the pole (push towards the
// lean), the rest are fixed random weights, and the logits are soft enough that it sometimes
// pushes the wrong way, so some episodes fall early and some reach the time limit.
PolicyNetwork SamplingPolicy(int input_size) {
  Random random(7);
  auto draw = [&random](int n) {
    std::vector<float> values(n);
    for (float& value : values) value = static_cast<float>(random.Normal(0, 0.3));
    return values;
  };
  DenseLayer hidden{
      .inputs = input_size, .outputs = 4, .weight = draw(4 * input_size), .bias = draw(4)};
  std::fill_n(hidden.weight.begin(), input_size, 0.0f);
  hidden.weight[2] = 20;  // theta
  hidden.weight[3] = 5;   // theta_dot
  hidden.bias[0] = 0;
  DenseLayer head{.inputs = 4,
                  .outputs = 2,
                  .weight = draw(8),
                  .bias = {0, 0},
                  .activation = Activation::kNone};
  head.weight[0] = -0.75f;  // push left's logit falls with the lean to the right
  head.weight[4] = 0.75f;
  absl::StatusOr<PolicyNetwork> policy =
      PolicyNetwork::Create({.layers = {hidden, head}, .num_actions = 2});
  EXPECT_TRUE(policy.ok()) << policy.status();
  return policy.value();
}

Vec MakeEnvs(std::vector<env::DynamicContextOptions> slots, int run_slots) {
  absl::StatusOr<Vec> envs = Vec::Create(std::move(slots), run_slots);
  EXPECT_TRUE(envs.ok()) << envs.status();
  return std::move(envs).value();
}

env::DynamicContextOptions SlotOptions(const run::RunPlan& plan, int slot) {
  env::DynamicContextOptions options = plan.slot;
  options.slot = static_cast<uint64_t>(slot);
  return options;
}

// The whole run in one VectorEnv, as `dcs train` collects it.
class WholeRun {
 public:
  explicit WholeRun(const run::RunPlan& plan) {
    std::vector<env::DynamicContextOptions> slots;
    for (int i = 0; i < kSlots; ++i) slots.push_back(SlotOptions(plan, i));
    envs_ = std::make_unique<Vec>(MakeEnvs(std::move(slots), /*run_slots=*/0));
    collector_ = std::make_unique<Collector>(*envs_, plan.slot.run_seed);
  }

  MergedRollout Collect(Policy& policy, int64_t rollout_index) {
    MergedRollout out;
    collector_->Collect(policy, kSteps, rollout_index, out.rollout, out.finished);
    out.journals = collector_->journals();
    return out;
  }

 private:
  std::unique_ptr<Vec> envs_;
  std::unique_ptr<Collector> collector_;  // borrows *envs_
};

// One slot of the run stepped alone, as an actor process would step it: new, or rebuilt from
// its journal at the run's step count `global_steps`.
class LoneSlot {
 public:
  LoneSlot(const run::RunPlan& plan, int slot, int64_t global_steps = 0,
           std::vector<SlotJournal> journal = {})
      : slot_(slot) {
    envs_ = std::make_unique<Vec>(MakeEnvs({SlotOptions(plan, slot)}, kSlots));
    envs_->set_global_steps(global_steps);
    collector_ = std::make_unique<Collector>(*envs_, plan.slot.run_seed, std::move(journal));
  }

  SlotRollout Collect(Policy& policy, int64_t rollout_index) {
    Rollout rollout;
    std::vector<EpisodeSummary> finished;
    collector_->Collect(policy, kSteps, rollout_index, rollout, finished);
    return MakeSlotRollout(std::move(rollout), slot_, std::move(finished),
                           collector_->journals().front());
  }

 private:
  int slot_;
  std::unique_ptr<Vec> envs_;
  std::unique_ptr<Collector> collector_;  // borrows *envs_
};

MergedRollout Merge(std::vector<std::unique_ptr<LoneSlot>>& slots, Policy& policy,
                    int64_t rollout_index) {
  // Collected in reverse, to show that neither the order of stepping nor of the parts matters.
  std::vector<SlotRollout> parts;
  for (int i = kSlots - 1; i >= 0; --i) parts.push_back(slots[i]->Collect(policy, rollout_index));
  absl::StatusOr<MergedRollout> merged = MergeSlotRollouts(std::move(parts));
  EXPECT_TRUE(merged.ok()) << merged.status();
  return std::move(merged).value();
}

// Exact equality, floats included.
void ExpectSame(const MergedRollout& got, const MergedRollout& want) {
  const Rollout& a = got.rollout;
  const Rollout& b = want.rollout;
  EXPECT_EQ(a.num_steps, b.num_steps);
  EXPECT_EQ(a.num_envs, b.num_envs);
  EXPECT_EQ(a.inputs, b.inputs);
  EXPECT_EQ(a.images, b.images);
  EXPECT_EQ(a.actions, b.actions);
  EXPECT_EQ(a.rewards, b.rewards);
  EXPECT_EQ(a.episode_starts, b.episode_starts);
  EXPECT_EQ(a.last_inputs, b.last_inputs);
  EXPECT_EQ(a.last_images, b.last_images);
  EXPECT_EQ(a.last_dones, b.last_dones);
  ASSERT_EQ(a.truncations.size(), b.truncations.size());
  for (size_t i = 0; i < a.truncations.size(); ++i) {
    EXPECT_EQ(a.truncations[i].step, b.truncations[i].step) << i;
    EXPECT_EQ(a.truncations[i].env, b.truncations[i].env) << i;
    EXPECT_EQ(a.truncations[i].input, b.truncations[i].input) << i;
    EXPECT_EQ(a.truncations[i].image, b.truncations[i].image) << i;
  }
  ASSERT_EQ(got.finished.size(), want.finished.size());
  for (size_t i = 0; i < got.finished.size(); ++i) {
    EXPECT_EQ(got.finished[i].episode_return, want.finished[i].episode_return) << i;
    EXPECT_EQ(got.finished[i].length, want.finished[i].length) << i;
    EXPECT_EQ(got.finished[i].step, want.finished[i].step) << i;
  }
  ASSERT_EQ(got.journals.size(), want.journals.size());
  for (size_t i = 0; i < got.journals.size(); ++i) {
    EXPECT_EQ(got.journals[i].episode, want.journals[i].episode) << i;
    EXPECT_EQ(got.journals[i].reset_step, want.journals[i].reset_step) << i;
    EXPECT_EQ(got.journals[i].actions, want.journals[i].actions) << i;
    EXPECT_EQ(got.journals[i].episode_return, want.journals[i].episode_return) << i;
  }
}

// What the run went through, so a test can show it covered the cases that matter: episodes
// that fell, episodes cut by the time limit, and resets (after the first) in both stages.
struct Coverage {
  int finished = 0;
  int truncations = 0;
  bool reset_in_first_stage = false;
  bool reset_in_second_stage = false;

  void Add(const MergedRollout& merged, int64_t boundary) {
    finished += static_cast<int>(merged.finished.size());
    truncations += static_cast<int>(merged.rollout.truncations.size());
    for (const SlotJournal& journal : merged.journals) {
      reset_in_first_stage |= journal.reset_step > 0 && journal.reset_step < boundary;
      reset_in_second_stage |= journal.reset_step >= boundary;
    }
  }
};

TEST(RolloutCollectorTest, SlotsCollectedApartMergeIntoTheWholeRunsRollouts) {
  const run::RunPlan plan = Plan();
  ASSERT_EQ(plan.stage_boundaries.size(), 1u);
  PolicyNetwork policy = SamplingPolicy(env::CartPole::kObservationSize + 1);
  WholeRun whole(plan);
  std::vector<std::unique_ptr<LoneSlot>> apart;
  for (int i = 0; i < kSlots; ++i) apart.push_back(std::make_unique<LoneSlot>(plan, i));
  Coverage coverage;
  for (int r = 0; r < kRollouts; ++r) {
    SCOPED_TRACE(testing::Message() << "rollout " << r);
    const MergedRollout want = whole.Collect(policy, r);
    ExpectSame(Merge(apart, policy, r), want);
    coverage.Add(want, plan.stage_boundaries[0]);
  }
  EXPECT_GT(coverage.finished, coverage.truncations);
  EXPECT_GT(coverage.truncations, 0);
  EXPECT_TRUE(coverage.reset_in_first_stage);
  EXPECT_TRUE(coverage.reset_in_second_stage);
}

TEST(RolloutCollectorTest, ASlotRebuiltFromItsJournalContinuesExactly) {
  const run::RunPlan plan = Plan();
  PolicyNetwork policy = SamplingPolicy(env::CartPole::kObservationSize + 1);
  WholeRun whole(plan);
  constexpr int kRebuildAfter = 5;  // at step 960, so the rebuilt slots cross the boundary
  std::vector<SlotJournal> journals;
  for (int r = 0; r < kRebuildAfter; ++r) journals = whole.Collect(policy, r).journals;

  // Each slot rebuilt alone from the journal the run's checkpoint would keep.
  const int64_t run_steps = int64_t{kRebuildAfter} * kSteps * kSlots;
  std::vector<std::unique_ptr<LoneSlot>> rebuilt;
  for (int i = 0; i < kSlots; ++i) {
    ASSERT_FALSE(journals[i].actions.empty()) << "slot " << i << " is not mid-episode";
    rebuilt.push_back(std::make_unique<LoneSlot>(plan, i, run_steps, std::vector{journals[i]}));
  }
  for (int r = kRebuildAfter; r < kRollouts; ++r) {
    SCOPED_TRACE(testing::Message() << "rollout " << r);
    ExpectSame(Merge(rebuilt, policy, r), whole.Collect(policy, r));
  }
}

}  // namespace
}  // namespace dcs::actor
