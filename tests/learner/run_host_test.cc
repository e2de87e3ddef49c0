// Copyright 2026 The DCS Authors.
//
// A run hosted for remote actors ends exactly as `dcs train` in one process ends: the same
// weights and evaluations, bit for bit, with slots stepped one at a time, changing hands, and
// the host restarted from a checkpoint. And it refuses what a stale or broken actor sends
// without harm to the run.

#include "learner/run_host.h"

#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "actor/slot_stepper.h"
#include "env/car_racing.h"
#include "env/cartpole.h"
#include "gmock/gmock.h"
#include "google/protobuf/util/field_comparator.h"
#include "google/protobuf/util/message_differencer.h"
#include "gtest/gtest.h"
#include "learner/torch_runtime.h"
#include "learner/training_run.h"
#include "tests/learner/small_run.h"

namespace dcs::learner {
namespace {

using ::testing::HasSubstr;

// The evaluation log without its wall-clock seconds.
v1::EvaluationLog WithoutSeconds(v1::EvaluationLog log) {
  for (v1::Evaluation& evaluation : *log.mutable_evaluations()) {
    for (v1::ContextEvaluation& context : *evaluation.mutable_contexts()) context.set_seconds(0);
  }
  return log;
}

void ExpectSameEvaluations(const v1::EvaluationLog& actual, const v1::EvaluationLog& expected) {
  google::protobuf::util::MessageDifferencer differencer;
  google::protobuf::util::DefaultFieldComparator comparator;
  comparator.set_treat_nan_as_equal(true);  // splits without contexts summarise to NaN
  differencer.set_field_comparator(&comparator);
  std::string differences;
  differencer.ReportDifferencesToString(&differences);
  EXPECT_TRUE(differencer.Compare(WithoutSeconds(actual), WithoutSeconds(expected)))
      << differences;
}

// The slots' holders, as actors would be: each slot a stepper of `Env` at a lease epoch.
template <typename Env = env::CartPole>
class Actors {
 public:
  explicit Actors(const run::RunSpec& spec) : spec_(spec) {}

  // Hands `slot` to a new holder at a newer epoch: it has to rebuild the slot.
  void HandOver(int slot) {
    steppers_.erase(slot);
    ++epochs_[slot];
  }

  int64_t epoch(int slot) { return epochs_[slot]; }

  // Every slot collects its part of the host's current rollout and pushes it.
  void CollectRollout(RunHost& host) {
    for (int slot = 0; slot < host.n_envs(); ++slot) {
      std::unique_ptr<actor::SlotStepper>& stepper = steppers_[slot];
      if (stepper == nullptr) {
        absl::StatusOr<run::RunPlan> plan = run::PlanRun(spec_, Env::Features());
        ASSERT_TRUE(plan.ok()) << plan.status();
        env::DynamicContextOptions options = plan->slot;
        options.slot = static_cast<uint64_t>(slot);
        absl::StatusOr<std::unique_ptr<actor::SlotStepper>> made =
            actor::MakeSlotStepper<Env>(options, spec_.n_envs);
        ASSERT_TRUE(made.ok()) << made.status();
        stepper = *std::move(made);
      }
      absl::StatusOr<SlotWork> work =
          host.GetSlotWork(slot, epoch(slot), stepper->positioned_at(), absl::ZeroDuration());
      ASSERT_TRUE(work.ok()) << work.status();
      ASSERT_TRUE(work->ready);
      EXPECT_EQ(work->journal.has_value(), stepper->positioned_at() != work->rollout);
      if (work->journal.has_value()) {
        stepper->Rebuild(*work->journal, work->rollout, work->start_timesteps);
      }
      absl::StatusOr<actor::PolicyNetwork> policy = actor::PolicyNetwork::Create(*work->weights);
      ASSERT_TRUE(policy.ok()) << policy.status();
      absl::StatusOr<bool> duplicate = host.PushRollout(epoch(slot), work->rollout, work->rollout,
                                                        stepper->Collect(*policy, work->n_steps));
      ASSERT_TRUE(duplicate.ok()) << duplicate.status();
      EXPECT_FALSE(*duplicate);
    }
  }

 private:
  const run::RunSpec spec_;
  std::map<int, std::unique_ptr<actor::SlotStepper>> steppers_;
  std::map<int, int64_t> epochs_;
};

std::unique_ptr<RunHost> NewHost(const run::Checkpoint* checkpoint = nullptr) {
  absl::StatusOr<std::unique_ptr<RunHost>> host =
      RunHost::Create<env::CartPole>(Spec(kSmallRun), checkpoint,
                                     EvaluateInProcess<env::CartPole>());
  EXPECT_TRUE(host.ok()) << host.status();
  return host.ok() ? *std::move(host) : nullptr;
}

class RunHostTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { PinTorchThreads(1).IgnoreError(); }

  static TrainingResult InOneProcess() {
    absl::StatusOr<TrainingResult> result = Train<env::CartPole>(Spec(kSmallRun), {});
    EXPECT_TRUE(result.ok()) << result.status();
    return result.value_or(TrainingResult{});
  }
};

TEST_F(RunHostTest, EndsAsTrainingInOneProcessDespiteHandoversAndARestart) {
  const TrainingResult expected = InOneProcess();
  Actors actors(Spec(kSmallRun));
  std::unique_ptr<RunHost> host = NewHost();
  ASSERT_NE(host, nullptr);
  std::optional<run::Checkpoint> checkpoint;
  v1::EvaluationLog log;
  for (int rollout = 0;; ++rollout) {
    if (rollout == 3) actors.HandOver(1);
    if (rollout == 5) actors.HandOver(0);
    if (rollout == 7) {
      // The learner dies; another resumes from the last checkpoint, which is older.
      ASSERT_TRUE(checkpoint.has_value());
      host = NewHost(&*checkpoint);
      ASSERT_NE(host, nullptr);
    }
    actors.CollectRollout(*host);
    absl::StatusOr<HostStep> step = host->Step();
    ASSERT_TRUE(step.ok()) << step.status();
    if (step->checkpoint.has_value()) {
      checkpoint = step->checkpoint;
      log = step->evaluation_log;
    }
    if (step->complete) break;
  }
  EXPECT_EQ(host->Parameters(), expected.parameters);
  ExpectSameEvaluations(log, expected.log);
}

TEST_F(RunHostTest, TellsASlotWhenTheRunIsComplete) {
  Actors actors(Spec(kSmallRun));
  std::unique_ptr<RunHost> host = NewHost();
  ASSERT_NE(host, nullptr);
  for (bool complete = false; !complete;) {
    actors.CollectRollout(*host);
    absl::StatusOr<HostStep> step = host->Step();
    ASSERT_TRUE(step.ok()) << step.status();
    complete = step->complete;
  }
  absl::StatusOr<SlotWork> work = host->GetSlotWork(0, 0, -1, absl::ZeroDuration());
  ASSERT_TRUE(work.ok());
  EXPECT_TRUE(work->run_complete);
  EXPECT_FALSE(work->ready);
}

TEST_F(RunHostTest, AHostResumedFromTheRunsEndIsCompleteAtOnce) {
  Actors actors(Spec(kSmallRun));
  std::unique_ptr<RunHost> host = NewHost();
  ASSERT_NE(host, nullptr);
  EXPECT_FALSE(host->complete());
  std::optional<run::Checkpoint> last;
  for (bool complete = false; !complete;) {
    actors.CollectRollout(*host);
    absl::StatusOr<HostStep> step = host->Step();
    ASSERT_TRUE(step.ok()) << step.status();
    if (step->checkpoint.has_value()) last = step->checkpoint;
    complete = step->complete;
  }
  // The checkpoint of the end, with the final evaluation: a learner that resumes from it has
  // nothing left to step (its slots are told so), and finishes the run at once.
  ASSERT_TRUE(last.has_value());
  ASSERT_EQ(last->state.timesteps, Spec(kSmallRun).total_timesteps);
  std::unique_ptr<RunHost> resumed = NewHost(&*last);
  ASSERT_NE(resumed, nullptr);
  EXPECT_TRUE(resumed->complete());
  absl::StatusOr<SlotWork> work = resumed->GetSlotWork(0, 1, -1, absl::ZeroDuration());
  ASSERT_TRUE(work.ok()) << work.status();
  EXPECT_TRUE(work->run_complete);
}

TEST_F(RunHostTest, AsksItsEvaluatorForThePolicyThatFellDueAndStoppingCancelsIt) {
  Actors actors(Spec(kSmallRun));
  absl::Mutex mu;
  std::vector<EvaluationDue> asked;
  std::vector<std::vector<float>> weights;
  absl::StatusOr<std::unique_ptr<RunHost>> created = RunHost::Create<env::CartPole>(
      Spec(kSmallRun), nullptr,
      [&](const EvaluationTask& task,
          const absl::Notification& stop) -> absl::StatusOr<actor::EvaluationResult> {
        {
          absl::MutexLock lock(&mu);
          asked.push_back(task.due);
          weights.push_back(task.weights->layers.back().weight);
        }
        stop.WaitForNotification();  // an evaluation that never ends by itself
        return absl::CancelledError("stopped");
      });
  ASSERT_TRUE(created.ok()) << created.status();
  std::unique_ptr<RunHost> host = *std::move(created);
  std::vector<float> version_1;  // the output layer as published for rollout 1
  for (int rollout = 0; rollout < 2; ++rollout) {
    if (rollout == 1) {
      absl::StatusOr<SlotWork> work = host->GetSlotWork(0, 0, -1, absl::ZeroDuration());
      ASSERT_TRUE(work.ok() && work->ready);
      version_1 = work->weights->layers.back().weight;
    }
    actors.CollectRollout(*host);
    ASSERT_TRUE(host->Step().ok());
  }
  {
    // Rollout 1 reached step 256: the policy that collected it, version 1, fell due.
    absl::MutexLock lock(&mu);
    mu.Await(absl::Condition(+[](std::vector<EvaluationDue>* a) { return !a->empty(); }, &asked));
    ASSERT_EQ(asked.size(), 1u);
    EXPECT_EQ(asked[0].policy_version, 1);
    EXPECT_EQ(asked[0].steps, std::vector<int64_t>{256});
    EXPECT_EQ(weights[0], version_1);
  }
  host->Stop();
  EXPECT_EQ(host->Step().status().code(), absl::StatusCode::kCancelled);
  host.reset();  // returns: the outstanding evaluation saw the stop
}

class RunHostInputTest : public RunHostTest {
 protected:
  void SetUp() override {
    host_ = NewHost();
    ASSERT_NE(host_, nullptr);
    absl::StatusOr<run::RunPlan> plan = run::PlanRun(Spec(kSmallRun), env::CartPole::Features());
    ASSERT_TRUE(plan.ok());
    env::DynamicContextOptions options = plan->slot;
    absl::StatusOr<std::unique_ptr<actor::SlotStepper>> stepper =
        actor::MakeSlotStepper<env::CartPole>(options, 2);
    ASSERT_TRUE(stepper.ok());
    absl::StatusOr<SlotWork> work = host_->GetSlotWork(0, 1, -1, absl::ZeroDuration());
    ASSERT_TRUE(work.ok() && work->journal.has_value());
    (*stepper)->Rebuild(*work->journal, 0, 0);
    absl::StatusOr<actor::PolicyNetwork> policy = actor::PolicyNetwork::Create(*work->weights);
    ASSERT_TRUE(policy.ok());
    part_ = (*stepper)->Collect(*policy, work->n_steps);
  }

  absl::StatusOr<bool> Push(actor::SlotRollout part, int64_t epoch = 1, int64_t rollout = 0,
                            int64_t version = 0) {
    return host_->PushRollout(epoch, rollout, version, std::move(part));
  }

  std::unique_ptr<RunHost> host_;
  actor::SlotRollout part_;
};

TEST_F(RunHostInputTest, TakesARetriedRolloutOnce) {
  EXPECT_EQ(Push(part_).value_or(true), false);
  EXPECT_EQ(Push(part_).value_or(false), true);
}

TEST_F(RunHostInputTest, RefusesAHolderWhoseLeaseMoved) {
  ASSERT_TRUE(host_->GetSlotWork(0, 2, -1, absl::ZeroDuration()).ok());
  const absl::Status stale = Push(part_, /*epoch=*/1).status();
  EXPECT_EQ(stale.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_EQ(stale.message(), "slot 0's lease moved to epoch 2; this holder has epoch 1");
}

TEST_F(RunHostInputTest, RefusesAStalePolicyVersionOrAFutureRollout) {
  EXPECT_EQ(Push(part_, 1, 0, /*version=*/3).status().code(),
            absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(Push(part_, 1, /*rollout=*/2, 2).status().message(),
              HasSubstr("rollout 2 is not being collected: rollout 0 is"));
}

TEST_F(RunHostInputTest, RefusesNonFiniteValuesAndWrongShapesNamingThem) {
  actor::SlotRollout nan = part_;
  nan.rewards[5] = std::numeric_limits<float>::quiet_NaN();
  absl::Status status = Push(nan).status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message(), "rewards at step 5 is nan; values must be finite");

  actor::SlotRollout inf = part_;
  inf.inputs[3] = std::numeric_limits<float>::infinity();
  EXPECT_THAT(Push(inf).status().message(), HasSubstr("inputs at step 0 is inf"));

  actor::SlotRollout short_inputs = part_;
  short_inputs.inputs.pop_back();
  EXPECT_THAT(Push(short_inputs).status().message(), HasSubstr("inputs has"));

  actor::SlotRollout bad_slot = part_;
  bad_slot.slot = 7;
  EXPECT_THAT(Push(bad_slot).status().message(), HasSubstr("slot 7 is not a slot of the run"));

  // None of it was taken: the good part still is.
  EXPECT_EQ(Push(part_).value_or(true), false);
}

TEST_F(RunHostTest, HostsImagePoliciesAsTrainingInOneProcessDoes) {
  const run::RunSpec spec = Spec(kSmallImageRun);
  absl::StatusOr<TrainingResult> expected = Train<env::CarRacing>(spec, {});
  ASSERT_TRUE(expected.ok()) << expected.status();
  absl::StatusOr<std::unique_ptr<RunHost>> host =
      RunHost::Create<env::CarRacing>(spec, nullptr, EvaluateInProcess<env::CarRacing>());
  ASSERT_TRUE(host.ok()) << host.status();
  Actors<env::CarRacing> actors(spec);
  v1::EvaluationLog log;
  for (int rollout = 0;; ++rollout) {
    if (rollout == 1) actors.HandOver(0);
    actors.CollectRollout(**host);
    absl::StatusOr<HostStep> step = (*host)->Step();
    ASSERT_TRUE(step.ok()) << step.status();
    if (step->checkpoint.has_value()) log = step->evaluation_log;
    if (step->complete) break;
  }
  EXPECT_EQ((*host)->Parameters(), expected->parameters);
  ExpectSameEvaluations(log, expected->log);
}

}  // namespace
}  // namespace dcs::learner
