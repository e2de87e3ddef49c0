// Copyright 2026 The DCS Authors.
//
// An exported policy in PyTorch acts as DCS does: check_export.py (beside this file) loads the
// state dict strictly into plain torch modules with Stable-Baselines3's layout, built from the
// layout JSON, and compares on 1,000 observations with DCS's deterministic actions
// (actor::PolicyNetwork, what DCS acts with) and values (the learner's forward pass). For a
// categorical, a Gaussian and an image policy, each after a few PPO updates on random rollouts
// (so no weight keeps its initial symmetry).

#include "learner/policy_export.h"

#include <stdio.h>
#include <sys/wait.h>

#include <cstdint>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "actor/policy_network.h"
#include "common/atomic_file.h"
#include "common/random.h"
#include "common/status_macros.h"
#include "env/env_registry.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "run/run_spec_yaml.h"
#include "tests/testing/temp_dir.h"

namespace dcs::learner {
namespace {

using ::testing::HasSubstr;

constexpr int kObservations = 1000;
constexpr int kSteps = 64;  // per rollout

// `values`' bytes, as numpy's fromfile reads them (x86-64: little endian).
template <typename T>
absl::Status WriteArray(const std::string& path, const std::vector<T>& values) {
  return WriteFileAtomically(
      path, absl::string_view(reinterpret_cast<const char*>(values.data()),
                              values.size() * sizeof(T)));
}

// `count` random policy inputs: flat inputs in [-2, 2] (the context's normalised values lie
// in [-5, 5], the environments' states mostly within a few units) and random images.
struct Observations {
  std::vector<float> inputs;
  std::vector<uint8_t> images;
};
Observations RandomObservations(const run::PolicySpec& spec, int count, Random& random) {
  Observations observations;
  observations.inputs.resize(static_cast<size_t>(count) * spec.flat_input_size());
  for (float& x : observations.inputs) x = static_cast<float>(random.Uniform(-2, 2));
  observations.images.resize(count * spec.image_size());
  for (uint8_t& pixel : observations.images) pixel = static_cast<uint8_t>(random.Integers(0, 256));
  return observations;
}

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
// three updates, as LoadTrainedPolicy gives it.
absl::StatusOr<TrainedPolicy> TrainedOn(const std::string& config) {
  TrainedPolicy trained;
  DCS_ASSIGN_OR_RETURN(trained.run.spec, run::ParseRunSpecYaml(config, "test config"));
  const run::RunSpec& run = trained.run.spec;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(run.env, [&]<typename Env>() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(trained.plan, run::PlanRun(run, Env::Features()));
    trained.policy = run::PolicySpecFor<Env>(
        static_cast<int>(trained.plan.slot.observed_features.size()));
    return absl::OkStatus();
  }));
  DCS_ASSIGN_OR_RETURN(trained.learner,
                       PpoLearner::Create(trained.policy, run.ppo, run.n_envs, run.seed));
  Random random(17);
  for (int update = 0; update < 3; ++update) {
    DCS_RETURN_IF_ERROR(
        trained.learner->Update(RandomRollout(trained.policy, random)).status());
  }
  return trained;
}

// check_export.py's output and exit code on `trained`'s export and DCS's outputs on
// kObservations random observations, in `dir`.
struct CheckResult {
  int exit_code = -1;
  std::string output;
};
CheckResult Check(const TrainedPolicy& trained, const std::string& dir) {
  absl::StatusOr<ExportedPolicy> exported = ExportPolicy(trained);
  EXPECT_TRUE(exported.ok()) << exported.status();
  const std::string policy_path = dir + "/policy.pt";
  EXPECT_TRUE(WriteExportedPolicy(*exported, policy_path).ok());

  Random random(29);
  const run::PolicySpec& spec = trained.policy;
  const Observations observations = RandomObservations(spec, kObservations, random);
  absl::StatusOr<actor::PolicyNetwork> network =
      actor::PolicyNetwork::Create(trained.learner->ActorWeights());
  EXPECT_TRUE(network.ok()) << network.status();
  std::vector<float> actions(static_cast<size_t>(kObservations) * spec.action_size);
  std::vector<Random> unused(kObservations, Random(0));  // deterministic: no draws
  network->Act(kObservations, observations.inputs, observations.images,
               /*deterministic=*/true, unused, actions);
  EXPECT_TRUE(WriteArray(dir + "/inputs.f32", observations.inputs).ok());
  EXPECT_TRUE(WriteArray(dir + "/images.u8", observations.images).ok());
  EXPECT_TRUE(WriteArray(dir + "/actions.f32", actions).ok());
  EXPECT_TRUE(WriteArray(
      dir + "/values.f32",
      trained.learner->Values(observations.inputs, observations.images, kObservations)).ok());

  // Debian's python3, where python3-torch installs (not a python3 earlier on PATH).
  const std::string command = absl::StrCat("/usr/bin/python3 ", DCS_CHECK_EXPORT_SCRIPT, " ",
                                           policy_path, " ", dir, " 2>&1");
  CheckResult result;
  FILE* pipe = popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr) << command;
  if (pipe == nullptr) return result;
  char buffer[4096];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.output.append(buffer, n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class PolicyExportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }
};

TEST_F(PolicyExportTest, CategoricalPolicyActsAsInDcs) {
  const absl::StatusOr<TrainedPolicy> trained = TrainedOn(R"(
env: cartpole
feature: length
training_range: [0.35, 0.75]
observe: live
evaluation: {contexts: {id: [0.5]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)");
  ASSERT_TRUE(trained.ok()) << trained.status();
  const CheckResult check = Check(*trained, testing::MakeTempDir());
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("1000 observations, agree"));
}

TEST_F(PolicyExportTest, GaussianPolicyActsAsInDcs) {
  const absl::StatusOr<TrainedPolicy> trained = TrainedOn(R"(
env: bipedal_walker
context: {PAYLOAD_MASS: 2.0, PAYLOAD_RADIUS: 0.5}
feature: COM_X
training_range: [-0.6, 0.6]
observe: live
evaluation: {contexts: {id: [0.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2}
)");
  ASSERT_TRUE(trained.ok()) << trained.status();
  const CheckResult check = Check(*trained, testing::MakeTempDir());
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("1000 observations, agree"));
}

TEST_F(PolicyExportTest, ImagePolicyWithContextBranchActsAsInDcs) {
  // The paper's CarRacing policy: the context through its own branch.
  const absl::StatusOr<TrainedPolicy> trained = TrainedOn(R"(
env: car_racing
context: {PAYLOAD_MASS: 1.0, PAYLOAD_RADIUS: 0.5}
feature: COM_Y
training_range: [-0.8, 0.8]
observe: live
evaluation: {contexts: {id: [0.0]}}
ppo: {n_steps: 64, batch_size: 32, n_epochs: 2, context_layers: [16]}
)");
  ASSERT_TRUE(trained.ok()) << trained.status();
  const CheckResult check = Check(*trained, testing::MakeTempDir());
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, HasSubstr("1000 observations, agree"));
}

TEST(PolicyExportLayoutTest, RefusesAStateDictPathEndingInJson) {
  EXPECT_TRUE(absl::IsInvalidArgument(LayoutPathFor("policy.json").status()));
  EXPECT_EQ(LayoutPathFor("out/policy.pt").value_or(""), "out/policy.json");
  EXPECT_EQ(LayoutPathFor("policy").value_or(""), "policy.json");
}

}  // namespace
}  // namespace dcs::learner
