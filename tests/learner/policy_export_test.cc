// Copyright 2026 The DCS Authors.
//
// An exported policy in PyTorch acts as DCS does (tests/learner/export_check.h), for a
// categorical, a Gaussian and an image policy, each after a few PPO updates on random rollouts
// (so no weight keeps its initial symmetry).

#include "learner/policy_export.h"

#include <cstdint>
#include <string>
#include <vector>

#include "common/random.h"
#include "common/status_macros.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "run/run_spec_yaml.h"
#include "tests/learner/export_check.h"
#include "tests/testing/temp_dir.h"

namespace dcs::learner {
namespace {

using ::testing::HasSubstr;

constexpr int kSteps = 64;  // per rollout

// A rollout of random observations, actions and rewards: enough for PPO to move every weight.
actor::Rollout RandomRollout(const run::PolicySpec& spec, Random& random) {
  Observations observations = RandomObservations(spec, kSteps + 1, random);
  actor::Rollout rollout{.num_steps = kSteps, .num_envs = 1};
  const size_t flat = spec.flat_input_size();
  rollout.inputs.assign(observations.inputs.begin(), observations.inputs.end() - flat);
  rollout.last_inputs.assign(observations.inputs.end() - flat, observations.inputs.end());
  rollout.images.assign(observations.images.begin(),
                        observations.images.end() - spec.image_size());
  rollout.last_images.assign(observations.images.end() - spec.image_size(),
                             observations.images.end());
  for (int t = 0; t < kSteps; ++t) {
    for (int a = 0; a < spec.action_size; ++a) {
      rollout.actions.push_back(spec.discrete()
                                    ? static_cast<float>(random.Integers(0, spec.num_actions))
                                    : static_cast<float>(random.Normal(0, 1)));
    }
    rollout.rewards.push_back(static_cast<float>(random.Normal(1, 1)));
    rollout.episode_starts.push_back(t % 16 == 0);
  }
  rollout.last_dones = {0};
  return rollout;
}

// The policy of a run of `config` (YAML, as run configs are written; n_steps: kSteps) after
// three updates on random rollouts.
absl::StatusOr<TrainedPolicy> TrainedOn(const std::string& config) {
  DCS_ASSIGN_OR_RETURN(run::RunSpec spec, run::ParseRunSpecYaml(config, "test config"));
  DCS_ASSIGN_OR_RETURN(TrainedPolicy trained,
                       NewTrainedPolicy({.spec = std::move(spec), .config_text = config}));
  Random random(17);
  for (int update = 0; update < 3; ++update) {
    DCS_RETURN_IF_ERROR(
        trained.learner->Update(RandomRollout(trained.policy, random)).status());
  }
  return trained;
}

// check_export.py on the export of a run of `config` (TrainedOn): PyTorch must act as DCS.
void ExpectExportActsAsInDcs(const std::string& config) {
  const absl::StatusOr<TrainedPolicy> trained = TrainedOn(config);
  ASSERT_TRUE(trained.ok()) << trained.status();
  absl::StatusOr<ExportedPolicy> exported = ExportPolicy(*trained);
  ASSERT_TRUE(exported.ok()) << exported.status();
  const std::string dir = testing::MakeTempDir();
  const std::string policy_path = dir + "/policy.pt";
  const absl::Status written = WriteExportedPolicy(*exported, policy_path);
  ASSERT_TRUE(written.ok()) << written;
  const ExportCheck check = CheckExport(*trained, policy_path, dir);
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("1000 observations, agree"));
}

class PolicyExportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }
};

TEST_F(PolicyExportTest, CategoricalPolicyActsAsInDcs) {
  ExpectExportActsAsInDcs(R"(
env: cartpole
feature: length
training_range: [0.35, 0.75]
observe: live
evaluation: {contexts: {id: [0.5]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)");
}

TEST_F(PolicyExportTest, GaussianPolicyActsAsInDcs) {
  ExpectExportActsAsInDcs(R"(
env: bipedal_walker
context: {PAYLOAD_MASS: 2.0, PAYLOAD_RADIUS: 0.5}
feature: COM_X
training_range: [-0.6, 0.6]
observe: live
evaluation: {contexts: {id: [0.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)");
}

TEST_F(PolicyExportTest, ImagePolicyWithContextBranchActsAsInDcs) {
  // The paper's CarRacing policy: the context through its own branch.
  ExpectExportActsAsInDcs(R"(
env: car_racing
context: {PAYLOAD_MASS: 1.0, PAYLOAD_RADIUS: 0.5}
feature: COM_Y
training_range: [-0.8, 0.8]
observe: live
evaluation: {contexts: {id: [0.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2, context_layers: [16]}
)");
}

TEST(PolicyExportLayoutTest, RefusesAStateDictPathEndingInJson) {
  EXPECT_TRUE(absl::IsInvalidArgument(LayoutPathFor("policy.json").status()));
  EXPECT_EQ(LayoutPathFor("out/policy.pt").value_or(""), "out/policy.json");
  EXPECT_EQ(LayoutPathFor("policy").value_or(""), "policy.json");
}

}  // namespace
}  // namespace dcs::learner
