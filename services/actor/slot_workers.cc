// Copyright 2026 The DCS Authors.
#include "services/actor/slot_workers.h"

#include <grpcpp/grpcpp.h>
#include <prometheus/counter.h>
#include <prometheus/histogram.h>

#include <optional>
#include <utility>
#include <vector>

#include "absl/random/random.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "actor/policy_network.h"
#include "actor/slot_stepper.h"
#include "common/status_macros.h"
#include "dcs/v1/learner_service.grpc.pb.h"
#include "env/env_registry.h"
#include "run/run_plan.h"
#include "run/run_spec_yaml.h"
#include "services/backoff.h"
#include "services/channel.h"
#include "services/finished_threads.h"
#include "services/lease_renewals.h"
#include "services/log.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/stream_call.h"
#include "services/time_proto.h"
#include "services/trajectory_proto.h"
#include "services/unary_call.h"

namespace dcs::services {

struct SlotWorkers::Slot {
  run::LeaseKey lease;
  std::string learner_address;
  int64_t learner_epoch = 0;
  std::string config;
  absl::Time renewed_at;  // the manager thread's

  std::atomic<bool> lost{false};  // the lease moved, lapsed or ended: stop
  std::atomic<bool> done{false};  // the slot's thread is about to return
  std::thread thread;
};

namespace {

constexpr BackoffPolicy kRetryBackoff{.initial = absl::Milliseconds(50),
                                      .max = absl::Seconds(1)};

// How many leases an actor remembers that a learner said its run is complete (10 minutes at
// the default 10 s lease): more than a final evaluation takes on a slow machine, short enough
// that a long sweep's ended runs do not pile up in every AcquireSlot.
constexpr int kCompleteLearnerLeases = 60;

std::string SlotName(const run::LeaseKey& lease) {
  return absl::StrCat(lease.run_id, "/", lease.slot);
}

// A slot's key among the held ones: a slot given up may be granted again before its old
// thread is reaped.
std::string LeaseName(const run::LeaseKey& lease) {
  return absl::StrCat(SlotName(lease), "@", lease.epoch);
}

// The stepper of slot `slot` of the run `config` describes.
absl::StatusOr<std::unique_ptr<actor::SlotStepper>> MakeStepper(const std::string& config,
                                                                const std::string& run_id,
                                                                int slot) {
  DCS_ASSIGN_OR_RETURN(const run::RunSpec spec, run::ParseRunSpecYaml(config, run_id));
  std::unique_ptr<actor::SlotStepper> stepper;
  DCS_RETURN_IF_ERROR(env::VisitEnvironment(spec.env, [&]<typename Env>() -> absl::Status {
    DCS_ASSIGN_OR_RETURN(run::RunPlan plan, run::PlanRun(spec, Env::Features()));
    plan.slot.slot = static_cast<uint64_t>(slot);
    DCS_ASSIGN_OR_RETURN(stepper, actor::MakeSlotStepper<Env>(plan.slot, spec.n_envs));
    return absl::OkStatus();
  }));
  return stepper;
}

}  // namespace

SlotWorkers::SlotWorkers(SlotWorkersOptions options, prometheus::Registry& metrics,
                         absl::Mutex& core)
    : options_(std::move(options)),
      coordinator_(v1::CoordinatorService::NewStub(OpenChannel(options_.coordinator_address))),
      steps_(prometheus::BuildCounter()
                 .Name("dcs_actor_env_steps_total")
                 .Help("Environment steps this actor took for training rollouts.")
                 .Register(metrics)
                 .Add({})),
      rollouts_(prometheus::BuildCounter()
                    .Name("dcs_actor_rollouts_total")
                    .Help("Slots' rollouts this actor delivered to learners.")
                    .Register(metrics)
                    .Add({})),
      rebuilds_(prometheus::BuildCounter()
                    .Name("dcs_actor_slot_rebuilds_total")
                    .Help("Slots rebuilt from their journals (taken over, or after a learner "
                          "resumed from a checkpoint).")
                    .Register(metrics)
                    .Add({})),
      update_latency_(prometheus::BuildHistogram()
                          .Name("dcs_policy_update_latency_seconds")
                          .Help("From a policy version's publication by the learner to this "
                                "actor's first step with it.")
                          .Register(metrics)
                          .Add({}, prometheus::Histogram::BucketBoundaries{
                                       0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                       0.25, 0.5, 1, 2.5, 5, 10})),
      core_(core),
      manager_([this] { Manage(); }) {}

SlotWorkers::~SlotWorkers() { Stop(); }

void SlotWorkers::Stop() {
  if (stopping_.HasBeenNotified()) return;  // stopped already
  stopping_.Notify();
  if (manager_.joinable()) manager_.join();
  std::map<std::string, std::shared_ptr<Slot>> slots;
  {
    absl::MutexLock lock(&mu_);
    slots.swap(slots_);
  }
  for (auto& [name, slot] : slots) {
    if (slot->thread.joinable()) slot->thread.join();
  }
}

void SlotWorkers::Manage() {
  while (!stopping_.HasBeenNotified()) {
    const absl::Time round = absl::Now();
    JoinFinished(mu_, slots_);
    RenewDueLeases(*coordinator_, options_.rpc_timeout, mu_, slots_, lease_duration_,
                   [](Slot& slot) { slot.lost = true; });
    AcquireSlot();
    // The rest of the round: an actor takes at most one slot a round, so that the actors share
    // the slots of runs that start together (each steps its slots on one core).
    stopping_.WaitForNotificationWithTimeout(options_.poll_interval - (absl::Now() - round));
  }
}

absl::Duration SlotWorkers::LeaseDuration() {
  absl::MutexLock lock(&mu_);
  return lease_duration_;
}

void SlotWorkers::AcquireSlot() {
  v1::AcquireSlotRequest request;
  request.set_holder(options_.holder);
  request.set_numerics(options_.numerics);
  *request.mutable_wait() = DurationToProto(options_.poll_interval);
  {
    absl::MutexLock lock(&mu_);
    if (static_cast<int>(slots_.size()) >= options_.max_slots) return;
    const absl::Time now = absl::Now();
    std::erase_if(complete_learners_,
                  [now](const auto& entry) { return entry.second.until <= now; });
    for (const auto& [name, learner] : complete_learners_) {
      *request.add_complete_learners() = LeaseToProto(learner.lease);
    }
  }
  v1::AcquireSlotResponse response;
  const absl::Status status =
      CallUnary(*coordinator_, &v1::CoordinatorService::Stub::AcquireSlot, request, response,
                options_.rpc_timeout, "coordinator");
  if (!status.ok() || !response.has_lease()) {
    if (!status.ok() && !IsTransient(status)) {
      Log(LogLevel::kWarning, "cannot take a slot", {{"error", status.ToString()}});
    }
    return;
  }
  absl::StatusOr<run::LeaseKey> lease = LeaseFromProto(response.lease());
  if (!lease.ok()) return;
  auto slot = std::make_shared<Slot>();
  slot->lease = *lease;
  slot->learner_address = response.learner_address();
  slot->learner_epoch = response.learner_epoch();
  slot->config = response.config();
  slot->renewed_at = absl::Now();
  Log(LogLevel::kInfo, "stepping a slot",
      {{"slot", SlotName(slot->lease)}, {"epoch", std::to_string(slot->lease.epoch)},
       {"learner", slot->learner_address}});
  absl::MutexLock lock(&mu_);
  lease_duration_ = DurationFromProto(response.lease_duration());
  slot->thread = std::thread([this, slot] {
    Work(*slot);
    slot->done = true;
  });
  slots_[LeaseName(slot->lease)] = std::move(slot);
}

void SlotWorkers::Work(Slot& slot) {
  const std::string name = SlotName(slot.lease);
  absl::StatusOr<std::unique_ptr<actor::SlotStepper>> stepper =
      MakeStepper(slot.config, slot.lease.run_id, slot.lease.slot);
  if (!stepper.ok()) {
    Log(LogLevel::kError, "cannot build a slot",
        {{"slot", name}, {"error", stepper.status().ToString()}});
    return;  // the lease lapses; nothing here can step this run
  }
  auto learner = v1::LearnerService::NewStub(OpenChannel(slot.learner_address));
  const v1::Lease lease = LeaseToProto(slot.lease);
  std::optional<actor::PolicyNetwork> policy;
  int64_t policy_version = -1;
  absl::Time learner_answered_at = absl::Now();
  absl::BitGen random;
  int failures = 0;

  // Gives the lease back when the slot is done with (the run ended, or the actor stops).
  auto release = [&](bool run_complete) {
    v1::ReleaseLeaseRequest request;
    *request.mutable_lease() = lease;
    request.set_run_complete(run_complete);
    v1::ReleaseLeaseResponse response;
    CallUnary(*coordinator_, &v1::CoordinatorService::Stub::ReleaseLease, request, response,
              options_.rpc_timeout, "coordinator")
        .IgnoreError();
  };
  auto log_failure = [&](const absl::Status& status) {
    Log(LogLevel::kWarning, "learner call failed",
        {{"slot", name}, {"error", status.ToString()}});
  };
  // The slot is worth keeping until its learner has been silent for a lease.
  auto learner_alive = [&] { return absl::Now() - learner_answered_at < LeaseDuration(); };

  // The manager thread renews the lease meanwhile (RenewDueLeases) and says when it is lost.
  while (!stopping_.HasBeenNotified() && !slot.lost) {
    v1::GetSlotWorkRequest ask;
    *ask.mutable_lease() = lease;
    ask.set_learner_epoch(slot.learner_epoch);
    ask.set_positioned_at((*stepper)->positioned_at());
    ask.set_policy_version(policy_version);
    *ask.mutable_wait() = DurationToProto(options_.work_wait);
    PieceJoiner<v1::GetSlotWorkResponse> reply(&v1::GetSlotWorkResponse::mutable_weights,
                                               "the policy");
    const absl::Status asked = CallServerStream(
        *learner, &v1::LearnerService::Stub::GetSlotWork, ask,
        options_.rpc_timeout + options_.work_wait, slot.learner_address,
        [&](v1::GetSlotWorkResponse& message) { return reply.Add(std::move(message)); });
    if (!asked.ok()) {
      if (IsTransient(asked)) {
        // Back off here rather than in CallWithRetries: the loop asks only while the lease holds.
        log_failure(asked);
        absl::SleepFor(BackoffDelay(kRetryBackoff, ++failures, random));
        if (learner_alive()) continue;
      }
      Log(LogLevel::kInfo, "giving up a slot", {{"slot", name}, {"error", asked.ToString()}});
      // At once, for another try, rather than when the lease lapses.
      release(/*run_complete=*/false);
      return;
    }
    learner_answered_at = absl::Now();
    failures = 0;
    const v1::GetSlotWorkResponse& work = reply.header();
    if (work.run_complete()) {
      {
        const run::LeaseKey complete{
            .run_id = slot.lease.run_id, .slot = run::kLearnerSlot, .epoch = slot.learner_epoch};
        absl::MutexLock lock(&mu_);
        complete_learners_[LeaseName(complete)] = {
            .lease = complete, .until = absl::Now() + kCompleteLearnerLeases * lease_duration_};
      }
      release(/*run_complete=*/true);
      return;
    }
    if (!work.ready()) continue;
    if (!reply.payload().empty()) {
      absl::StatusOr<actor::PolicyNetwork> made = PolicyFromBytes(reply.payload());
      if (!made.ok()) {
        Log(LogLevel::kError, "bad policy from the learner",
            {{"slot", name}, {"error", made.status().ToString()}});
        return;
      }
      policy = *std::move(made);
      policy_version = work.rollout();
    }
    if (work.has_journal()) {
      absl::StatusOr<actor::SlotJournal> journal = JournalFromProto(work.journal());
      if (!journal.ok()) {
        Log(LogLevel::kError, "bad journal from the learner",
            {{"slot", name}, {"error", journal.status().ToString()}});
        return;
      }
      (*stepper)->Rebuild(*journal, work.rollout(), work.start_timesteps());
      rebuilds_.Increment();
    }
    if (!policy.has_value() || policy_version != work.rollout() ||
        (*stepper)->positioned_at() != work.rollout()) {
      // The learner answered as if we held what we do not: ask again from scratch.
      policy_version = -1;
      continue;
    }

    std::string data;
    {
      absl::MutexLock on_core(&core_);
      update_latency_.Observe(
          absl::ToDoubleSeconds(absl::Now() - TimeFromProto(work.publish_time())));
      data = SlotRolloutToProto((*stepper)->Collect(*policy, work.n_steps())).SerializeAsString();
    }
    steps_.Increment(work.n_steps());
    v1::PushRolloutRequest header;
    *header.mutable_lease() = lease;
    header.set_learner_epoch(slot.learner_epoch);
    header.set_rollout(work.rollout());
    header.set_policy_version(policy_version);
    const std::vector<v1::PushRolloutRequest> push =
        CutIntoMessages(std::move(header), data, &v1::PushRolloutRequest::mutable_data);
    v1::PushRolloutResponse pushed;
    const absl::Status status = CallClientStreamWithRetries(
        *learner, &v1::LearnerService::Stub::PushRollout, push, pushed, options_.rpc_timeout,
        slot.learner_address, kRetryBackoff, [&](const absl::Status& failed) {
          log_failure(failed);
          return !stopping_.HasBeenNotified() && !slot.lost && learner_alive();
        });
    if (!status.ok()) {
      if (stopping_.HasBeenNotified() || slot.lost) break;
      Log(LogLevel::kInfo, "giving up a slot", {{"slot", name}, {"error", status.ToString()}});
      return;
    }
    rollouts_.Increment();
    learner_answered_at = absl::Now();
  }
  if (!slot.lost) release(/*run_complete=*/false);  // a lost lease is another holder's now
}

}  // namespace dcs::services
