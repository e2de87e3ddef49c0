// Copyright 2026 The DCS Authors.
//
// The session's contract, step by step: what falls due when, with which policy version;
// what it refuses; and that a session made from its checkpoint continues exactly.

#include "learner/training_session.h"

#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "actor/policy_network.h"
#include "actor/rollout_collector.h"
#include "env/cartpole.h"
#include "env/vector_env.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "tests/learner/small_run.h"

namespace dcs::learner {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A session with its own environment slots, stepped as an actor would step them.
class Driver {
 public:
  // nullptr (with a test failure) if the session or its slots cannot be made.
  static std::unique_ptr<Driver> Make(const run::Checkpoint* checkpoint = nullptr) {
    absl::StatusOr<std::unique_ptr<TrainingSession>> session =
        TrainingSession::Create<env::CartPole>(Spec(kSmallRun), checkpoint);
    EXPECT_TRUE(session.ok()) << session.status();
    if (!session.ok()) return nullptr;
    std::vector<env::DynamicContextOptions> slots(2, (*session)->plan().slot);
    slots[1].slot = 1;
    absl::StatusOr<env::VectorEnv<env::CartPole>> envs =
        env::VectorEnv<env::CartPole>::Create(std::move(slots));
    EXPECT_TRUE(envs.ok()) << envs.status();
    if (!envs.ok()) return nullptr;
    return std::unique_ptr<Driver>(new Driver(*std::move(session), *std::move(envs)));
  }

  TrainingSession& session() { return *session_; }

  // Collects the next rollout with the session's current policy and adds it.
  absl::StatusOr<std::optional<EvaluationDue>> Collect() {
    absl::StatusOr<actor::PolicyNetwork> policy =
        actor::PolicyNetwork::Create(session_->ActorWeights());
    if (!policy.ok()) return policy.status();
    actor::Rollout rollout;
    std::vector<actor::EpisodeSummary> finished;
    collector_->Collect(*policy, session_->spec().ppo.n_steps, session_->state().rollouts, rollout,
                        finished);
    return session_->AddRollout(std::move(rollout), finished, collector_->journals());
  }

 private:
  Driver(std::unique_ptr<TrainingSession> session, env::VectorEnv<env::CartPole> envs)
      : session_(std::move(session)), envs_(std::move(envs)) {
    envs_.set_global_steps(session_->state().timesteps);
    collector_.emplace(envs_, session_->spec().seed, session_->state().journals);
  }

  std::unique_ptr<TrainingSession> session_;
  env::VectorEnv<env::CartPole> envs_;
  std::optional<actor::RolloutCollector<env::CartPole>> collector_;  // borrows envs_
};

class TrainingSessionTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }
};

TEST_F(TrainingSessionTest, EvaluationsFallDueWithThePolicyThatCollectedTheStep) {
  std::unique_ptr<Driver> driver = Driver::Make();
  ASSERT_NE(driver, nullptr);
  TrainingSession& session = driver->session();
  std::vector<std::pair<std::vector<int64_t>, int64_t>> due;
  std::vector<bool> checkpoints;
  while (!session.complete()) {
    absl::StatusOr<std::optional<EvaluationDue>> added = driver->Collect();
    ASSERT_TRUE(added.ok()) << added.status();
    if (added->has_value()) due.emplace_back((*added)->steps, (*added)->policy_version);
    const int64_t version = session.policy_version();
    absl::StatusOr<SessionUpdate> update = session.Update();
    ASSERT_TRUE(update.ok()) << update.status();
    EXPECT_EQ(session.policy_version(), version + 1);
    if (update->final_evaluation.has_value()) {
      due.emplace_back(update->final_evaluation->steps, update->final_evaluation->policy_version);
    }
    checkpoints.push_back(session.checkpoint_due());
  }
  // Rollout 4 (steps 385-512) reaches the boundary 400 and step 512: one evaluation for both.
  EXPECT_THAT(due, ElementsAre(std::pair{std::vector<int64_t>{256}, 1},
                               std::pair{std::vector<int64_t>{400, 512}, 3},
                               std::pair{std::vector<int64_t>{768}, 5},
                               std::pair{std::vector<int64_t>{1024}, 7},
                               std::pair{std::vector<int64_t>{1280}, 9},
                               std::pair{std::vector<int64_t>{1280}, 10}));
  EXPECT_THAT(checkpoints, ElementsAre(false, true, false, true, false, true, false, true, false,
                                       true));
  EXPECT_EQ(session.state().rollouts, 10);
}

TEST_F(TrainingSessionTest, RecordsOneEvaluationAtEachStepItWasDueAt) {
  std::unique_ptr<Driver> driver = Driver::Make();
  ASSERT_NE(driver, nullptr);
  TrainingSession& session = driver->session();
  actor::EvaluationResult result{.contexts = {{.context = {.value = 0.5}, .returns = {7}}}};
  actor::Summarize(result);
  session.RecordEvaluation({.steps = {400, 512}, .policy_version = 3}, result);
  ASSERT_EQ(session.state().evaluations.size(), 2u);
  EXPECT_EQ(session.state().evaluations[1].step, 512);
  EXPECT_EQ(session.state().evaluations[1].updates, 3);
  EXPECT_EQ(session.EvaluationLog().evaluations_size(), 2);
  EXPECT_FALSE(session.EvaluationLog().complete());
}

TEST_F(TrainingSessionTest, RefusesStepsOutOfOrderOrOfTheWrongShape) {
  std::unique_ptr<Driver> driver = Driver::Make();
  ASSERT_NE(driver, nullptr);
  TrainingSession& session = driver->session();
  EXPECT_EQ(session.Update().status().code(), absl::StatusCode::kFailedPrecondition);
  ASSERT_TRUE(driver->Collect().ok());
  const absl::Status twice = driver->Collect().status();
  EXPECT_EQ(twice.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(twice.message(), HasSubstr("rollout 0 waits for its update"));
  ASSERT_TRUE(session.Update().ok());

  actor::Rollout short_rollout{.num_steps = 32, .num_envs = 2};
  const absl::Status shape =
      session.AddRollout(short_rollout, {}, session.state().journals).status();
  EXPECT_EQ(shape.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(shape.message(), HasSubstr("has 32 steps of 2 slots"));
  EXPECT_EQ(session.state().timesteps, 128);
}

TEST_F(TrainingSessionTest, ASessionFromItsCheckpointContinuesExactly) {
  std::unique_ptr<Driver> straight = Driver::Make();
  std::unique_ptr<Driver> first = Driver::Make();
  ASSERT_TRUE(straight != nullptr && first != nullptr);
  for (int i = 0; i < 3; ++i) {
    for (Driver* driver : {straight.get(), first.get()}) {
      ASSERT_TRUE(driver->Collect().ok());
      ASSERT_TRUE(driver->session().Update().ok());
    }
  }
  absl::StatusOr<run::Checkpoint> checkpoint = first->session().Checkpoint();
  ASSERT_TRUE(checkpoint.ok()) << checkpoint.status();
  EXPECT_EQ(checkpoint->name, "000000000384");
  std::unique_ptr<Driver> resumed = Driver::Make(&*checkpoint);
  ASSERT_NE(resumed, nullptr);
  EXPECT_EQ(resumed->session().policy_version(), 3);
  for (int i = 0; i < 3; ++i) {
    for (Driver* driver : {straight.get(), resumed.get()}) {
      ASSERT_TRUE(driver->Collect().ok());
      ASSERT_TRUE(driver->session().Update().ok());
    }
  }
  EXPECT_EQ(resumed->session().Parameters(), straight->session().Parameters());
  EXPECT_EQ(resumed->session().state().recent_returns, straight->session().state().recent_returns);
  EXPECT_EQ(resumed->session().state().recent_lengths, straight->session().state().recent_lengths);
}

TEST_F(TrainingSessionTest, EpisodeLengthIsSb3sEpLenMeanOverTheLastHundredEpisodes) {
  std::unique_ptr<Driver> driver = Driver::Make();
  ASSERT_NE(driver, nullptr);
  EXPECT_TRUE(std::isnan(driver->session().recent_episode_length()));
  for (int i = 0; i < 6; ++i) {
    ASSERT_TRUE(driver->Collect().ok());
    ASSERT_TRUE(driver->session().Update().ok());
  }
  const run::RunState& state = driver->session().state();
  ASSERT_EQ(state.recent_lengths.size(), state.recent_returns.size());
  ASSERT_GT(state.recent_lengths.size(), 10u);
  // CartPole pays 1 for every step, the terminating one included, so an episode's return is
  // its length as SB3's Monitor counts it (ep_len_mean).
  for (size_t i = 0; i < state.recent_lengths.size(); ++i) {
    EXPECT_EQ(static_cast<double>(state.recent_lengths[i]), state.recent_returns[i]) << i;
  }
  EXPECT_EQ(driver->session().recent_episode_length(), driver->session().recent_return());
}

TEST_F(TrainingSessionTest, RefusesACheckpointOfAnotherRun) {
  std::unique_ptr<Driver> driver = Driver::Make();
  ASSERT_NE(driver, nullptr);
  ASSERT_TRUE(driver->Collect().ok());
  ASSERT_TRUE(driver->session().Update().ok());
  absl::StatusOr<run::Checkpoint> checkpoint = driver->session().Checkpoint();
  ASSERT_TRUE(checkpoint.ok());
  run::RunSpec other_seed = Spec(kSmallRun);
  other_seed.seed = 12;
  EXPECT_EQ(TrainingSession::Create<env::CartPole>(other_seed, &*checkpoint).status().code(),
            absl::StatusCode::kFailedPrecondition);
  run::RunSpec other_slots = Spec(kSmallRun);
  other_slots.n_envs = 4;
  const absl::Status slots =
      TrainingSession::Create<env::CartPole>(other_slots, &*checkpoint).status();
  EXPECT_EQ(slots.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(slots.message(), HasSubstr("checkpoint 000000000128 has 2 environment slots"));
}

}  // namespace
}  // namespace dcs::learner
