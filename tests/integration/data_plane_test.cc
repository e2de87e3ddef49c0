// Copyright 2026 The DCS Authors.
//
// The distributed actor-learner end to end, with real processes on loopback: a run submitted
// to a cluster ends with the same weights and evaluation log, bit for bit, as `dcs train` in
// one process: with one actor, with three, and after kill -9 of an actor, of the learner, or
// of the coordinator (restarted on its data directory).

#include <grpcpp/grpcpp.h>
#include <signal.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "actor/policy_network.h"
#include "actor/slot_stepper.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "dcs/v1/learner_service.grpc.pb.h"
#include "dcs/proto_json.h"
#include "env/cartpole.h"
#include "env/env_registry.h"
#include "gmock/gmock.h"
#include "google/protobuf/util/field_comparator.h"
#include "google/protobuf/util/message_differencer.h"
#include "gtest/gtest.h"
#include "learner/training_session.h"
#include "run/appended_evaluation_log.h"
#include "run/evaluation_log.h"
#include "run/run_plan.h"
#include "run/run_checkpoint.h"
#include "run/run_directory.h"
#include "run/run_spec_yaml.h"
#include "run/sweep_spec_yaml.h"
#include "services/cli/child_process.h"
#include "services/cli/cluster_client.h"
#include "services/cli/run_client.h"
#include "services/channel.h"
#include "services/pieces.h"
#include "services/port_file.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/trajectory_proto.h"
#include "services/unary_call.h"
#include "tests/integration/cluster_processes.h"
#include "tests/integration/test_util.h"
#include "tests/learner/small_run.h"
#include "tests/testing/net.h"
#include "tests/testing/temp_dir.h"
#include "tests/testing/slowdown.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using services::cli::ChildProcess;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::Not;

// The learner tests' run (learner::CartPoleRun) with three slots, evaluations with checkpoints
// between them: 10 rollouts of 3 x 256 steps.
const std::string kConfig = learner::CartPoleRun(
    {.seed = 5, .total_timesteps = 7680, .n_envs = 3, .first_stage_steps = 3000,
     .evaluation_freq = 1536, .evaluation_episodes = 3, .n_steps = 256, .batch_size = 64});

// An image policy (NatureCNN on CarRacing's frames, the context through its own branch), two
// slots: its policy (4.5 MB) and each slot's rollout (48 frames of 27 kB) are larger than one
// message and travel in pieces.
const std::string kImageConfig = learner::CarRacingRun(
    {.seed = 3, .evaluation_freq = 96, .n_steps = 48, .context_branch = true});

// kImageConfig without the context branch, as a sweep through `dcs submit`: static and a
// sinusoid, one seed.
constexpr char kImageSweepSpec[] = R"(name: car_racing_small
seeds: [3]
observe: [live]
env: car_racing
total_timesteps: 192
n_envs: 2
feature: COM_Y
training_range: [-0.8, 0.8]
pool: {size: 3}
evaluation: {freq: 96, episodes: 1, contexts: {id: [0.0]}}
ppo: {n_steps: 48, batch_size: 48, n_epochs: 2}
conditions:
  - name: static
  - schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 40}
)";

constexpr absl::Duration kLease = absl::Seconds(1);
constexpr absl::Duration kTimeout = absl::Seconds(5);

// What a finished run left: its evaluation log and its final weights.
struct RunOutcome {
  v1::EvaluationLog log;
  std::vector<float> parameters;
};

// The outcome of run `config` stored in `dir`, as `dcs train` lays a run out. Weights are
// compared as loaded back, not as bytes: libtorch's serialisation is not byte-stable.
std::optional<RunOutcome> ReadOutcome(const std::string& dir, const std::string& config = kConfig) {
  absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(dir);
  EXPECT_TRUE(log.ok()) << log.status();
  absl::StatusOr<run::Checkpoint> checkpoint = run::ReadLatestCheckpoint(dir);
  EXPECT_TRUE(checkpoint.ok()) << checkpoint.status();
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(config, "config");
  EXPECT_TRUE(spec.ok()) << spec.status();
  if (!log.ok() || !checkpoint.ok() || !spec.ok()) return std::nullopt;
  std::unique_ptr<learner::TrainingSession> session;
  const absl::Status made = env::VisitEnvironment(spec->env, [&]<typename Env>() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(session, learner::TrainingSession::Create<Env>(*spec, &*checkpoint));
    return absl::OkStatus();
  });
  EXPECT_TRUE(made.ok()) << made;
  if (!made.ok()) return std::nullopt;
  EXPECT_TRUE(session->complete()) << dir << " holds an unfinished run";
  return RunOutcome{.log = *std::move(log), .parameters = session->Parameters()};
}

// The same evaluation log but for the seconds each evaluation took.
void ExpectSameLog(const v1::EvaluationLog& actual, const v1::EvaluationLog& expected) {
  google::protobuf::util::MessageDifferencer differencer;
  google::protobuf::util::DefaultFieldComparator comparator;
  comparator.set_treat_nan_as_equal(true);  // a split without contexts summarises to NaN
  differencer.set_field_comparator(&comparator);
  differencer.IgnoreField(v1::ContextEvaluation::descriptor()->FindFieldByName("seconds"));
  std::string differences;
  differencer.ReportDifferencesToString(&differences);
  EXPECT_TRUE(differencer.Compare(actual, expected)) << differences;
}

void ExpectSameOutcome(const RunOutcome& actual, const RunOutcome& expected) {
  EXPECT_EQ(actual.parameters, expected.parameters) << "final weights differ";
  ExpectSameLog(actual.log, expected.log);
}

// Run `config` as `dcs train` trains it in one process.
RunOutcome TrainInOneProcess(const std::string& config) {
  const std::string dir = testing::MakeTempDir();
  const std::string file = dir + "/run.yaml";
  EXPECT_TRUE(WriteFileAtomically(file, config).ok());
  const RunResult trained = RunProgram(
      BinaryPath("dcs"), {"train", "--config", file, "--out", dir + "/run"}, absl::Minutes(5));
  EXPECT_EQ(trained.exit_code, 0) << trained.output;
  return ReadOutcome(dir + "/run", config).value_or(RunOutcome{});
}

// kConfig's run in one process: the reference, made once.
const RunOutcome& InOneProcess() {
  static const RunOutcome* outcome = new RunOutcome(TrainInOneProcess(kConfig));
  return *outcome;
}

// The cluster of processes, and the runs the tests submit to it.
class Cluster : public ClusterProcesses {
 public:
  Cluster() : ClusterProcesses(kLease) {}

  // Submits the run of `config`; returns its id.
  std::string Submit(const std::string& config = kConfig) {
    absl::StatusOr<v1::Run> run = services::cli::SubmitRun(coordinator_address(), config,
                                                           "run.yaml", std::nullopt, kTimeout);
    EXPECT_TRUE(run.ok()) << run.status();
    return run.ok() ? run->run_id() : "";
  }

  // Waits until run `run_id` has learnt from at least `timesteps` steps.
  void WaitForProgress(const std::string& run_id, int64_t timesteps) {
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(2));
    while (absl::Now() < deadline) {
      absl::StatusOr<v1::Run> run = services::cli::GetRun(coordinator_address(), run_id, kTimeout);
      if (run.ok() && run->progress().timesteps() >= timesteps) return;
      absl::SleepFor(absl::Milliseconds(20));
    }
    FAIL() << run_id << " did not reach step " << timesteps << "; logs in " << dir();
  }

  // Waits for the run of `config` to end, downloads it, and reads what it left.
  std::optional<RunOutcome> Finish(const std::string& run_id, const std::string& config = kConfig) {
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Minutes(4));
    absl::StatusOr<v1::Run> run = services::cli::WatchRun(
        coordinator_address(), run_id,
        {.on_update = [](const v1::Run&) {},
         .interrupted = [deadline] { return absl::Now() > deadline; }});
    EXPECT_TRUE(run.ok()) << run.status() << "; logs in " << dir();
    if (!run.ok()) return std::nullopt;
    EXPECT_EQ(run->state(), v1::RUN_STATE_COMPLETED) << run->error() << "; logs in " << dir();
    const std::string out = dir() + "/out/" + run_id;
    absl::Status downloaded =
        services::cli::DownloadRun(coordinator_address(), run_id, out, kTimeout);
    EXPECT_TRUE(downloaded.ok()) << downloaded;
    return ReadOutcome(out, config);
  }
};

class DataPlaneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { InOneProcess(); }
};

TEST_F(DataPlaneTest, OneActorGivesTheRunOfOneProcess) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  cluster.StartActor("actor", 64);
  std::optional<RunOutcome> outcome = cluster.Finish(cluster.Submit());
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, InOneProcess());

  // The metrics of the run, on every process, pass promtool's lint; the run's own series left
  // the learner with the run. The actor ran every evaluation: 6 policy versions (steps 1536 to
  // 7680, and the final policy) on 2 contexts. Each of the 3 slots was granted once: not again
  // once the learner had said the run was complete.
  const std::map<std::string, std::vector<std::string>> expected = {
      {"coordinator",
       {"dcs_runs{state=\"completed\"} 1", "dcs_leases_granted_total{kind=\"slot\"} 3\n",
        "dcs_leases_granted_total{kind=\"evaluation\"} 12",
        "dcs_queue_depth{queue=\"evaluations\"} 0"}},
      {"learner", {"dcs_learner_update_seconds_count 10", "dcs_rollouts_received_total 30"}},
      {"actor",
       {"dcs_actor_rollouts_total 30", "dcs_policy_update_latency_seconds_count 30",
        "dcs_actor_evaluation_jobs_total 12"}}};
  for (const auto& [name, series] : expected) {
    absl::StatusOr<std::string> exposition = testing::HttpGet(cluster.metrics_url(name));
    ASSERT_TRUE(exposition.ok()) << exposition.status();
    for (const std::string& one : series) EXPECT_THAT(*exposition, HasSubstr(one)) << name;
    EXPECT_THAT(*exposition, Not(HasSubstr("run_id=\"run-1\""))) << name;
    const std::string file = absl::StrCat(testing::MakeTempDir(), "/metrics.txt");
    ASSERT_TRUE(WriteFileAtomically(file, *exposition).ok());
    const RunResult lint =
        RunProgram("/bin/sh", {"-c", absl::StrCat("promtool check metrics < ", file)});
    EXPECT_EQ(lint.exit_code, 0) << name << ": " << lint.output;
  }
}

TEST_F(DataPlaneTest, ThreeActorsGiveTheRunOfOneProcess) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  for (const char* actor : {"actor-1", "actor-2", "actor-3"}) cluster.StartActor(actor, 1);
  std::optional<RunOutcome> outcome = cluster.Finish(cluster.Submit());
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, InOneProcess());
}

TEST_F(DataPlaneTest, AnImagePolicyOnTwoActorsGivesTheRunOfOneProcess) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  for (const char* actor : {"actor-1", "actor-2"}) cluster.StartActor(actor, 1);
  std::optional<RunOutcome> outcome =
      cluster.Finish(cluster.Submit(kImageConfig), kImageConfig);
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, TrainInOneProcess(kImageConfig));
}

// A CarRacing sweep submitted with `dcs submit`: each of its runs is the run its trial's config
// gives in one process.
TEST_F(DataPlaneTest, AnImageSweepGivesTheRunsOfOneProcess) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  for (const char* actor : {"actor-1", "actor-2"}) cluster.StartActor(actor, 1);
  const std::string spec = cluster.dir() + "/car_racing_small.yaml";
  ASSERT_TRUE(WriteFileAtomically(spec, kImageSweepSpec).ok());
  const RunResult submitted =
      DcsAt({"submit", spec, "--watch"}, cluster.coordinator_address(), absl::Minutes(5));
  ASSERT_EQ(submitted.exit_code, 0) << submitted.output << "; logs in " << cluster.dir();
  EXPECT_THAT(submitted.output, HasSubstr("car_racing_small: completed, 2/2 runs done"));

  absl::StatusOr<run::SweepSpec> sweep = run::ParseSweepSpecYaml(kImageSweepSpec, "sweep.yaml");
  ASSERT_TRUE(sweep.ok()) << sweep.status();
  absl::StatusOr<std::vector<v1::Run>> runs =
      services::cli::ListRuns(cluster.coordinator_address(), kTimeout);
  ASSERT_TRUE(runs.ok()) << runs.status();
  ASSERT_EQ(runs->size(), 2u);
  for (const v1::Run& run : *runs) {
    ASSERT_TRUE(run.has_trial());
    SCOPED_TRACE(sweep->trials.at(run.trial()).condition);
    const std::string config =
        run::ConfigWithSeed(sweep->trials.at(run.trial()).config, run.seed());
    std::optional<RunOutcome> outcome = cluster.Finish(run.run_id(), config.c_str());
    ASSERT_TRUE(outcome.has_value());
    ExpectSameOutcome(*outcome, TrainInOneProcess(config.c_str()));
  }
}

TEST_F(DataPlaneTest, AKilledActorsSlotsAreRebuiltByAnother) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  cluster.StartActor("doomed", 3);
  const std::string run_id = cluster.Submit();
  cluster.WaitForProgress(run_id, 2304);
  // Killed before the survivor starts: started first, it could find the run already finished
  // by the doomed actor (the rest of it takes a fraction of a second) and step nothing.
  cluster.Kill("doomed");
  cluster.StartActor("survivor", 3);
  std::optional<RunOutcome> outcome = cluster.Finish(run_id);
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, InOneProcess());
  // The survivor took over the slots mid-run (the doomed actor held all three).
  EXPECT_THAT(cluster.Log("survivor"), HasSubstr("stepping a slot"));
}

TEST_F(DataPlaneTest, AKilledLearnersRunResumesOnAnotherFromItsCheckpoint) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("doomed");
  cluster.StartActor("actor", 64);
  const std::string run_id = cluster.Submit();
  cluster.WaitForProgress(run_id, 3840);  // past the first checkpoint (after step 1536)
  cluster.Kill("doomed");
  cluster.StartLearner("survivor");
  std::optional<RunOutcome> outcome = cluster.Finish(run_id);
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, InOneProcess());
  EXPECT_THAT(cluster.Log("survivor"),
              ContainsRegex("hosting a run run_id=run-1 epoch=2 checkpoint=0000000"));
  // The coordinator appended each checkpoint's new evaluations, the survivor's after the doomed
  // learner's: its log is the one of one process, each evaluation once.
  const std::string stored = absl::StrCat(cluster.data_dir(), "/runs/", run_id);
  ASSERT_TRUE(run::HasAppendedEvaluationLog(stored));
  absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(stored);
  ASSERT_TRUE(log.ok()) << log.status();
  ExpectSameLog(*log, InOneProcess().log);
  const std::string lines = ReadFile(stored + "/evaluations.jsonl").value_or("");
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), InOneProcess().log.evaluations_size());
}

TEST_F(DataPlaneTest, AKilledCoordinatorRestartsOnItsDataAndLosesNothing) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  cluster.StartActor("actor", 64);
  const std::string run_id = cluster.Submit();
  cluster.WaitForProgress(run_id, 2304);
  cluster.Kill("coordinator");
  absl::SleepFor(2 * kLease);  // longer than a lease
  // A restarted coordinator gives held leases a full lease from its start to be renewed in.
  // Workers reconnect after gRPC's reconnect backoff (1 s, +-20 %), so the restarted one's
  // leases last longer than that; a 1 s lease could lapse before the learner is back.
  cluster.StartCoordinator(3 * kLease);
  std::optional<RunOutcome> outcome = cluster.Finish(run_id);
  ASSERT_TRUE(outcome.has_value());
  ExpectSameOutcome(*outcome, InOneProcess());
  // The run ended under the restarted coordinator, with the lease it had before.
  const std::string log = cluster.Log("coordinator");
  const size_t restart = log.rfind("coordinator: started");
  ASSERT_NE(restart, std::string::npos);
  EXPECT_NE(log.find("run finished run_id=run-1 state=completed", restart), std::string::npos)
      << log;
  EXPECT_EQ(log.find("run leased", restart), std::string::npos) << log;
}

// An actor's side of the wire, played by the test: a slot lease and calls to the learner.
class FakeActor {
 public:
  FakeActor(const std::string& coordinator, const std::string& learner)
      : coordinator_(v1::CoordinatorService::NewStub(services::OpenChannel(coordinator))),
        learner_(v1::LearnerService::NewStub(services::OpenChannel(learner))) {}

  // Takes slot 0's lease (waiting for the learner to take the run first).
  v1::AcquireSlotResponse AcquireSlot(const std::string& holder) {
    v1::AcquireSlotRequest request;
    request.set_holder(holder);
    request.set_numerics(kActorNumerics);
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
    while (absl::Now() < deadline) {
      v1::AcquireSlotResponse response;
      const absl::Status status =
          services::CallUnary(*coordinator_, &v1::CoordinatorService::Stub::AcquireSlot, request,
                              response, kTimeout, "coordinator");
      EXPECT_TRUE(status.ok()) << status;
      if (response.has_lease()) return response;
      absl::SleepFor(absl::Milliseconds(50));
    }
    ADD_FAILURE() << "no slot to take";
    return {};
  }

  // The work of the slot and its policy, joined from their pieces.
  struct Work {
    v1::GetSlotWorkResponse work;
    std::string weights;  // a serialised PolicyWeights
  };

  absl::StatusOr<Work> GetWork(const v1::AcquireSlotResponse& slot) {
    v1::GetSlotWorkRequest request;
    *request.mutable_lease() = slot.lease();
    request.set_learner_epoch(slot.learner_epoch());
    request.set_positioned_at(-1);
    request.set_policy_version(-1);
    const absl::Time deadline = absl::Now() + testing::Patient(absl::Seconds(30));
    while (true) {  // UNAVAILABLE while the learner loads the run
      services::PieceJoiner<v1::GetSlotWorkResponse> reply(
          &v1::GetSlotWorkResponse::mutable_weights, "the policy");
      const absl::Status status = services::CallServerStream(
          *learner_, &v1::LearnerService::Stub::GetSlotWork, request, kTimeout, "learner",
          [&](v1::GetSlotWorkResponse& message) { return reply.Add(std::move(message)); });
      if (status.ok()) return Work{reply.header(), reply.payload()};
      if (!absl::IsUnavailable(status) || absl::Now() > deadline) return status;
    }
  }

  // Pushes the stream of `messages`.
  absl::StatusOr<v1::PushRolloutResponse> Push(
      const std::vector<v1::PushRolloutRequest>& messages) {
    v1::PushRolloutResponse response;
    DCS_RETURN_IF_ERROR(services::CallClientStream(*learner_,
                                                   &v1::LearnerService::Stub::PushRollout,
                                                   messages, response, kTimeout, "learner"));
    return response;
  }

  // Pushes `data` under `header`, in pieces as actors do.
  absl::StatusOr<v1::PushRolloutResponse> Push(const v1::PushRolloutRequest& header,
                                               const v1::SlotRollout& data) {
    return Push(services::CutIntoMessages(header, data.SerializeAsString(),
                                          &v1::PushRolloutRequest::mutable_data));
  }

  // What the actor DCS ships computes with (services/actor/actor_main.cc): the run pins it.
  static constexpr char kActorNumerics[] = "the test's";

 private:
  std::unique_ptr<v1::CoordinatorService::Stub> coordinator_;
  std::unique_ptr<v1::LearnerService::Stub> learner_;
};

// Slot 0's part of rollout 0, as an actor collects it with the policy of `work`.
v1::SlotRollout CollectSlot0(const FakeActor::Work& work) {
  absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(kConfig, "config");
  absl::StatusOr<run::RunPlan> plan = run::PlanRun(*spec, env::CartPole::Features());
  EXPECT_TRUE(plan.ok()) << plan.status();
  absl::StatusOr<std::unique_ptr<actor::SlotStepper>> stepper =
      actor::MakeSlotStepper<env::CartPole>(plan->slot, spec->n_envs);
  absl::StatusOr<actor::SlotJournal> journal = services::JournalFromProto(work.work.journal());
  absl::StatusOr<actor::PolicyNetwork> policy = services::PolicyFromBytes(work.weights);
  EXPECT_TRUE(stepper.ok() && journal.ok() && policy.ok());
  (*stepper)->Rebuild(*journal, work.work.rollout(), work.work.start_timesteps());
  return services::SlotRolloutToProto((*stepper)->Collect(*policy, work.work.n_steps()));
}

// One slot whose two pieces of work (BipedalWalker rollouts of 2^16 steps) each take longer
// than a lease: the actor's manager thread renews the lease while the slot's thread steps, so
// no lease lapses and the slot is never taken again and rebuilt.
constexpr char kLongPieceConfig[] = R"(env: bipedal_walker
seed: 11
total_timesteps: 131072
n_envs: 1
feature: GRAVITY_Y
training_range: [-12.0, -8.0]
evaluation: {freq: 131072, episodes: 1, contexts: {id: [-10.0]}}
ppo: {n_steps: 65536, batch_size: 8192, n_epochs: 1}
)";

TEST_F(DataPlaneTest, AnActorKeepsASlotWhosePiecesOfWorkOutlastALease) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  cluster.StartActor("actor", 1);
  const absl::Time submitted = absl::Now();
  ASSERT_TRUE(cluster.Finish(cluster.Submit(kLongPieceConfig), kLongPieceConfig).has_value());
  // The premise: two pieces (and two quick updates) took longer than two leases.
  ASSERT_GT(absl::Now() - submitted, 2 * kLease);
  absl::StatusOr<std::string> metrics = testing::HttpGet(cluster.metrics_url("coordinator"));
  ASSERT_TRUE(metrics.ok()) << metrics.status();
  EXPECT_EQ(MetricValue(*metrics, "dcs_leases_expired_total"), 0) << "logs in " << cluster.dir();
}

TEST(DataPlaneBadInputTest, RefusesEachBadRolloutNamingItAndTakesTheGoodOne) {
  Cluster cluster;
  cluster.StartCoordinator();
  cluster.StartLearner("learner");
  const std::string run_id = cluster.Submit();
  FakeActor actor(cluster.coordinator_address(), cluster.address("learner"));
  const v1::AcquireSlotResponse slot = actor.AcquireSlot("fake-actor");
  ASSERT_EQ(slot.lease().run_id(), run_id);
  absl::StatusOr<FakeActor::Work> work = actor.GetWork(slot);
  ASSERT_TRUE(work.ok()) << work.status();
  ASSERT_TRUE(work->work.ready());
  v1::PushRolloutRequest header;
  *header.mutable_lease() = slot.lease();
  header.set_learner_epoch(slot.learner_epoch());
  header.set_rollout(0);
  header.set_policy_version(0);
  const v1::SlotRollout data = CollectSlot0(*work);

  struct Case {
    const char* what;
    std::function<void(v1::PushRolloutRequest&, v1::SlotRollout&)> spoil;
    absl::StatusCode code;
    const char* message;
  };
  const Case cases[] = {
      {"unknown run", [](auto& r, auto&) { r.mutable_lease()->set_run_id("run-99"); },
       absl::StatusCode::kNotFound, "this learner does not host run-99"},
      {"stale learner epoch",
       [](auto& r, auto&) { r.set_learner_epoch(r.learner_epoch() + 7); },
       absl::StatusCode::kFailedPrecondition, "another learner lease epoch"},
      {"stale policy version", [](auto& r, auto&) { r.set_policy_version(3); },
       absl::StatusCode::kFailedPrecondition, "collected with policy version 0, not 3"},
      {"a rollout not being collected",
       [](auto& r, auto&) {
         r.set_rollout(4);
         r.set_policy_version(4);
       },
       absl::StatusCode::kFailedPrecondition, "rollout 4 is not being collected"},
      {"wrong observation size",
       [](auto&, auto& d) {
         v1::Tensor& inputs = *d.mutable_inputs();
         inputs.set_shape(1, inputs.shape(1) - 1);
         inputs.mutable_data()->resize(inputs.shape(0) * inputs.shape(1) * sizeof(float));
       },
       absl::StatusCode::kInvalidArgument, "inputs has"},
      {"tensor shape not its length",
       [](auto&, auto& d) { d.mutable_rewards()->mutable_data()->resize(12); },
       absl::StatusCode::kInvalidArgument, "rewards: shape [256] of D_TYPE_FLOAT32 needs 1024"},
      {"NaN",
       [](auto&, auto& d) {
         const float nan = std::numeric_limits<float>::quiet_NaN();
         std::memcpy(d.mutable_rewards()->mutable_data()->data() + 8, &nan, 4);
       },
       absl::StatusCode::kInvalidArgument, "rewards at step 2 is nan"},
      {"infinity",
       [](auto&, auto& d) {
         const float inf = std::numeric_limits<float>::infinity();
         std::memcpy(d.mutable_inputs()->mutable_data()->data(), &inf, 4);
       },
       absl::StatusCode::kInvalidArgument, "inputs at step 0 is inf"},
  };
  for (const Case& bad : cases) {
    v1::PushRolloutRequest spoilt_header = header;
    v1::SlotRollout spoilt_data = data;
    bad.spoil(spoilt_header, spoilt_data);
    const absl::Status status = actor.Push(spoilt_header, spoilt_data).status();
    EXPECT_EQ(status.code(), bad.code) << bad.what << ": " << status;
    EXPECT_THAT(status.message(), HasSubstr(bad.message)) << bad.what;
  }
  // What breaks the stream itself: a piece over gRPC's message limit (refused by gRPC, before
  // the learner sees it), pieces that do not parse, no message at all.
  v1::PushRolloutRequest oversized = header;
  oversized.mutable_data()->resize(5 << 20);
  EXPECT_EQ(actor.Push({oversized}).status().code(), absl::StatusCode::kResourceExhausted);
  v1::PushRolloutRequest garbage = header;
  garbage.set_data("not a rollout");
  EXPECT_THAT(actor.Push({garbage}).status().message(),
              HasSubstr("the slot's rollout (13 bytes in pieces) does not parse"));
  EXPECT_THAT(actor.Push({}).status().message(), HasSubstr("the stream was empty"));

  // The run and the process are unharmed: the good rollout is taken, once.
  absl::StatusOr<v1::PushRolloutResponse> taken = actor.Push(header, data);
  ASSERT_TRUE(taken.ok()) << taken.status();
  EXPECT_FALSE(taken->duplicate());
  taken = actor.Push(header, data);
  ASSERT_TRUE(taken.ok()) << taken.status();
  EXPECT_TRUE(taken->duplicate());

  // The holder whose lease moved is refused: the slot lapses and goes to another holder.
  absl::SleepFor(kLease + absl::Milliseconds(500));
  FakeActor other(cluster.coordinator_address(), cluster.address("learner"));
  const v1::AcquireSlotResponse again = other.AcquireSlot("another-fake-actor");
  EXPECT_EQ(again.lease().slot(), 0);
  EXPECT_GT(again.lease().epoch(), slot.lease().epoch());
  ASSERT_TRUE(other.GetWork(again).ok());
  const absl::Status moved = actor.Push(header, data).status();
  EXPECT_EQ(moved.code(), absl::StatusCode::kFailedPrecondition) << moved;
  EXPECT_THAT(moved.message(), HasSubstr("slot 0's lease moved to epoch"));

  // Each refusal the learner itself made is counted under its reason; the hosted run has its
  // series, from zero.
  absl::StatusOr<std::string> metrics = testing::HttpGet(cluster.metrics_url("learner"));
  ASSERT_TRUE(metrics.ok()) << metrics.status();
  // A run alone: no sweep or condition.
  constexpr char kRun[] = R"({condition="",observe="",run_id="run-1",sweep_id=""})";
  EXPECT_EQ(MetricValue(*metrics, absl::StrCat("dcs_env_steps_total", kRun)), 0);
  EXPECT_EQ(MetricValue(*metrics, absl::StrCat("dcs_episodes_total", kRun)), 0);
  // The shapes and values, the pieces that do not parse, the empty stream and the one gRPC cut
  // short (it looks empty to the learner).
  EXPECT_EQ(MetricValue(*metrics, "dcs_rollouts_rejected_total{reason=\"INVALID_ARGUMENT\"}"), 7);
  EXPECT_EQ(MetricValue(*metrics, "dcs_rollouts_rejected_total{reason=\"FAILED_PRECONDITION\"}"),
            4);
  EXPECT_EQ(MetricValue(*metrics, "dcs_rollouts_rejected_total{reason=\"NOT_FOUND\"}"), 1);
  EXPECT_EQ(MetricValue(*metrics, "dcs_rollouts_received_total"), 1);
}

// Calls the coordinator's `method`, failing the test unless it succeeds.
template <typename Request, typename Response>
Response CallCoordinator(v1::CoordinatorService::Stub& coordinator,
                         grpc::Status (v1::CoordinatorService::Stub::*method)(
                             grpc::ClientContext*, const Request&, Response*),
                         const Request& request) {
  Response response;
  const absl::Status status =
      services::CallUnary(coordinator, method, request, response, kTimeout, "coordinator");
  EXPECT_TRUE(status.ok()) << status;
  return response;
}

// An evaluation job, as an actor takes it: the job and its policy joined from their pieces.
struct Job {
  v1::AcquireEvaluationResponse job;
  v1::PolicyWeights weights;
};

Job AcquireJob(v1::CoordinatorService::Stub& coordinator,
               const v1::AcquireEvaluationRequest& request) {
  services::PieceJoiner<v1::AcquireEvaluationResponse> reply(
      &v1::AcquireEvaluationResponse::mutable_weights, "the evaluation's policy");
  const absl::Status status = services::CallServerStream(
      coordinator, &v1::CoordinatorService::Stub::AcquireEvaluation, request, kTimeout,
      "coordinator",
      [&](v1::AcquireEvaluationResponse& message) { return reply.Add(std::move(message)); });
  EXPECT_TRUE(status.ok()) << status;
  Job job{.job = reply.header()};
  EXPECT_TRUE(reply.Parse(job.weights).ok());
  return job;
}

// A learner's part, played by the test: the lease of the queued run.
v1::AcquireRunResponse TakeRunAsLearner(v1::CoordinatorService::Stub& coordinator) {
  v1::AcquireRunRequest request;
  request.set_holder("fake-learner");
  request.set_address("127.0.0.1:1");
  return CallCoordinator(coordinator, &v1::CoordinatorService::Stub::AcquireRun, request);
}

TEST(DataPlaneBadInputTest, RefusesEachBadEvaluationResultNamingItAndTakesTheGoodOne) {
  Cluster cluster;
  cluster.StartCoordinator();
  const std::string run_id = cluster.Submit();
  auto coordinator =
      v1::CoordinatorService::NewStub(services::OpenChannel(cluster.coordinator_address()));
  using Stub = v1::CoordinatorService::Stub;

  const v1::AcquireRunResponse run = TakeRunAsLearner(*coordinator);
  ASSERT_EQ(run.lease().run_id(), run_id);
  v1::SubmitEvaluationRequest submit;
  *submit.mutable_lease() = run.lease();
  submit.set_contexts(2);
  submit.set_episodes(3);
  v1::PolicyWeights weights;
  weights.set_num_actions(2);
  v1::SubmitEvaluationResponse submitted;
  const absl::Status not_weights = services::CallClientStream(
      *coordinator, &Stub::SubmitEvaluation,
      services::CutIntoMessages(submit, "not weights",
                                &v1::SubmitEvaluationRequest::mutable_weights),
      submitted, kTimeout, "coordinator");
  EXPECT_THAT(not_weights.message(), HasSubstr("the evaluation's policy (11 bytes in pieces)"));
  const absl::Status submitted_status = services::CallClientStream(
      *coordinator, &Stub::SubmitEvaluation,
      services::CutIntoMessages(submit, weights.SerializeAsString(),
                                &v1::SubmitEvaluationRequest::mutable_weights),
      submitted, kTimeout, "coordinator");
  ASSERT_TRUE(submitted_status.ok()) << submitted_status;

  v1::AcquireEvaluationRequest acquire_job;
  acquire_job.set_holder("fake-actor");
  const Job acquired = AcquireJob(*coordinator, acquire_job);
  const v1::AcquireEvaluationResponse& job = acquired.job;
  ASSERT_EQ(job.jobs_size(), 1);  // it asked for no more
  EXPECT_EQ(job.episodes(), 3);
  EXPECT_EQ(acquired.weights.num_actions(), 2);
  v1::ReportEvaluationRequest good;
  *good.add_results()->mutable_job() = job.jobs(0);
  for (double value : {1.0, 2.0, 3.0}) {
    good.mutable_results(0)->mutable_result()->add_returns(value);
  }

  struct Case {
    const char* what;
    std::function<void(v1::ReportEvaluationRequest&)> spoil;
    absl::StatusCode code;
    const char* message;
  };
  const Case cases[] = {
      {"unknown run", [](auto& r) { r.mutable_results(0)->mutable_job()->set_run_id("run-99"); },
       absl::StatusCode::kNotFound, "context 0 of policy version 0 of run-99 does not exist"},
      {"unknown context", [](auto& r) { r.mutable_results(0)->mutable_job()->set_context(9); },
       absl::StatusCode::kNotFound, "context 9"},
      {"too few returns",
       [](auto& r) { r.mutable_results(0)->mutable_result()->mutable_returns()->RemoveLast(); },
       absl::StatusCode::kInvalidArgument, "has 3 episodes; 2 returns were delivered"},
      {"NaN",
       [](auto& r) {
         r.mutable_results(0)->mutable_result()->set_returns(
             1, std::numeric_limits<double>::quiet_NaN());
       },
       absl::StatusCode::kInvalidArgument, "the return of episode 1"},
      {"no result", [](auto& r) { r.clear_results(); }, absl::StatusCode::kInvalidArgument,
       "holds no job's result"},
  };
  for (const Case& bad : cases) {
    v1::ReportEvaluationRequest request = good;
    bad.spoil(request);
    v1::ReportEvaluationResponse response;
    const absl::Status status = services::CallUnary(*coordinator, &Stub::ReportEvaluation,
                                                    request, response, kTimeout, "coordinator");
    EXPECT_EQ(status.code(), bad.code) << bad.what << ": " << status;
    EXPECT_THAT(status.message(), HasSubstr(bad.message)) << bad.what;
  }
  // The good result is taken, once.
  EXPECT_FALSE(CallCoordinator(*coordinator, &Stub::ReportEvaluation, good).duplicate(0));
  EXPECT_TRUE(CallCoordinator(*coordinator, &Stub::ReportEvaluation, good).duplicate(0));

  // A holder whose job lapsed and went to another still delivers it: the result is the same
  // whoever computes it. The new holder's is then a duplicate; an epoch never granted is refused.
  const v1::AcquireEvaluationResponse lapsing = AcquireJob(*coordinator, acquire_job).job;
  ASSERT_EQ(lapsing.jobs(0).context(), 1);
  absl::SleepFor(kLease * 0.6);
  v1::RenewLeaseRequest renew;  // the learner stays
  *renew.mutable_lease() = run.lease();
  CallCoordinator(*coordinator, &Stub::RenewLease, renew);
  absl::SleepFor(kLease * 0.6);
  const v1::AcquireEvaluationResponse again = AcquireJob(*coordinator, acquire_job).job;
  ASSERT_EQ(again.jobs(0).context(), 1);
  EXPECT_GT(again.jobs(0).epoch(), lapsing.jobs(0).epoch());
  v1::ReportEvaluationRequest late = good;
  *late.mutable_results(0)->mutable_job() = lapsing.jobs(0);
  EXPECT_FALSE(CallCoordinator(*coordinator, &Stub::ReportEvaluation, late).duplicate(0));
  v1::ReportEvaluationRequest current = good;
  *current.mutable_results(0)->mutable_job() = again.jobs(0);
  EXPECT_TRUE(CallCoordinator(*coordinator, &Stub::ReportEvaluation, current).duplicate(0));
  v1::ReportEvaluationRequest forged = current;
  forged.mutable_results(0)->mutable_job()->set_epoch(again.jobs(0).epoch() + 1);
  v1::ReportEvaluationResponse refused;
  const absl::Status never = services::CallUnary(*coordinator, &Stub::ReportEvaluation, forged,
                                                 refused, kTimeout, "coordinator");
  EXPECT_EQ(never.code(), absl::StatusCode::kFailedPrecondition) << never;
  EXPECT_THAT(never.message(), HasSubstr("never granted"));

  // Each refusal is counted under its reason.
  absl::StatusOr<std::string> metrics = testing::HttpGet(cluster.metrics_url("coordinator"));
  ASSERT_TRUE(metrics.ok()) << metrics.status();
  EXPECT_EQ(MetricValue(*metrics, "dcs_requests_rejected_total{reason=\"NOT_FOUND\"}"), 2);
  EXPECT_EQ(MetricValue(*metrics, "dcs_requests_rejected_total{reason=\"INVALID_ARGUMENT\"}"),
            4);
  EXPECT_EQ(
      MetricValue(*metrics, "dcs_requests_rejected_total{reason=\"FAILED_PRECONDITION\"}"), 1);
}

TEST(DataPlaneStreamTest, ACheckpointLargerThanAMessageTravelsInPieces) {
  Cluster cluster;
  cluster.StartCoordinator();
  const std::string run_id = cluster.Submit();
  auto coordinator =
      v1::CoordinatorService::NewStub(services::OpenChannel(cluster.coordinator_address()));
  using Stub = v1::CoordinatorService::Stub;
  const v1::AcquireRunResponse run = TakeRunAsLearner(*coordinator);
  ASSERT_EQ(run.lease().run_id(), run_id);

  // 6 MiB of learner state: over gRPC's 4 MiB message limit.
  const run::PackedCheckpoint packed = run::PackCheckpoint(
      {.name = run::CheckpointName(768),
       .state = {.timesteps = 768, .rollouts = 1},
       .learner = std::string(6 << 20, 'w')});
  std::vector<v1::PutCheckpointRequest> put;
  for (const v1::CheckpointPiece& piece : services::CheckpointToPieces(packed)) {
    *put.emplace_back().mutable_checkpoint() = piece;
  }
  *put.front().mutable_lease() = run.lease();
  put.front().set_evaluation_log(v1::EvaluationLog().SerializeAsString());
  v1::PutCheckpointResponse stored;
  ASSERT_TRUE(services::CallClientStream(*coordinator, &Stub::PutCheckpoint, put, stored,
                                         kTimeout, "coordinator")
                  .ok());

  // The learner that resumes gets it whole; so does `dcs runs get`.
  v1::GetCheckpointRequest get;
  *get.mutable_lease() = run.lease();
  run::PackedCheckpoint fetched;
  bool first = true;
  ASSERT_TRUE(services::CallServerStream(*coordinator, &Stub::GetCheckpoint, get, kTimeout,
                                         "coordinator",
                                         [&](const v1::CheckpointPiece& piece) {
                                           const absl::Status added =
                                               services::AddCheckpointPiece(piece, first,
                                                                            fetched);
                                           first = false;
                                           return added;
                                         })
                  .ok());
  EXPECT_EQ(fetched.name, packed.name);
  EXPECT_EQ(fetched.learner, packed.learner);
  EXPECT_EQ(fetched.run_state, packed.run_state);
  const std::string dir = testing::MakeTempDir();
  ASSERT_TRUE(services::cli::DownloadRun(cluster.coordinator_address(), run_id, dir, kTimeout)
                  .ok());
  EXPECT_EQ(fs::file_size(fs::path(dir) / "checkpoints" / packed.name / "learner.bin"),
            size_t{6} << 20);

  // A stream whose checkpoint does not match its SHA-256 stores nothing.
  put.back().mutable_checkpoint()->mutable_learner()->back() = 'x';
  const absl::Status corrupt = services::CallClientStream(
      *coordinator, &Stub::PutCheckpoint, put, stored, kTimeout, "coordinator");
  EXPECT_EQ(corrupt.code(), absl::StatusCode::kDataLoss) << corrupt;
}

TEST(DataPlaneBadInputTest, AMalformedConfigSubmittedRemotelyNamesItsFieldAndLine) {
  Cluster cluster;
  cluster.StartCoordinator();
  std::string config = kConfig;
  config.replace(config.find("n_envs: 3"), 9, "n_envs: 0");
  const absl::Status status = services::cli::SubmitRun(cluster.coordinator_address(), config,
                                                       "bad.yaml", std::nullopt, kTimeout)
                                  .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << status;
  EXPECT_THAT(status.message(), HasSubstr("bad.yaml: n_envs: line 4"));
  // Nothing was queued.
  absl::StatusOr<std::vector<v1::Run>> runs =
      services::cli::ListRuns(cluster.coordinator_address(), kTimeout);
  ASSERT_TRUE(runs.ok()) << runs.status();
  EXPECT_TRUE(runs->empty());
}

}  // namespace
}  // namespace dcs::integration
