// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_ACTOR_SLOT_WORKERS_H_
#define DCS_SERVICES_ACTOR_SLOT_WORKERS_H_

// An actor's work (docs/architecture.md §9): env slots leased from the coordinator, stepped for
// their runs' learners. Stateless between leases. A manager thread takes slot leases while fewer
// than max_slots are held and renews them (services/lease_renewals.h); each slot has a thread that
// asks the run's learner for work (waiting there for the next policy version), rebuilds the slot
// from its journal when it is not positioned where the learner says (actor/slot_stepper.h),
// collects the slot's part of the rollout with the policy (Eigen) and pushes it, retrying a learner
// that does not answer. A piece of work may thus take longer than a lease (an image policy under a
// sanitizer, a slot waiting for the core). Slots step holding the actor's core (a mutex shared with
// its evaluation jobs: services/actor/evaluation_worker.h), so an actor uses one core and the slots
// of many runs share it: while one waits for its run's update, another steps.
//
// A slot is given up when its lease is lost (it moved, lapsed, or the run ended) or its
// learner stops answering for longer than a lease: the coordinator then hands it out again.
//
// Thread-safe. The destructor stops everything.

#include <prometheus/counter.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>

#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include "absl/base/thread_annotations.h"
#include "absl/synchronization/mutex.h"
#include "absl/synchronization/notification.h"
#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "run/lease_key.h"

namespace dcs::services {

struct SlotWorkersOptions {
  std::string coordinator_address;
  std::string holder;    // the actor's name in leases
  std::string numerics;  // the numeric libraries' fingerprint
  int max_slots = 64;
  // How long the coordinator may hold a request for a slot while none is free (a long poll),
  // and so how often an actor that has found none asks again.
  absl::Duration poll_interval = absl::Milliseconds(200);
  absl::Duration rpc_timeout = absl::Seconds(10);
  absl::Duration work_wait = absl::Seconds(2);  // how long a learner may hold GetSlotWork
};

class SlotWorkers {
 public:
  // Starts the manager thread. Borrows `metrics` and `core`, which must outlive this.
  SlotWorkers(SlotWorkersOptions options, prometheus::Registry& metrics, absl::Mutex& core);
  ~SlotWorkers();
  SlotWorkers(const SlotWorkers&) = delete;
  SlotWorkers& operator=(const SlotWorkers&) = delete;

  // Stops taking slots, stops every slot's thread and gives the leases back.
  void Stop();

 private:
  struct Slot;

  void Manage();
  // Takes a slot (waiting up to a poll interval at the coordinator for one) and starts its
  // thread, if it has room for one.
  void AcquireSlot();
  // The coordinator's lease duration, as it last said.
  absl::Duration LeaseDuration();
  void Work(Slot& slot);

  const SlotWorkersOptions options_;
  const std::unique_ptr<v1::CoordinatorService::Stub> coordinator_;
  prometheus::Counter& steps_;
  prometheus::Counter& rollouts_;
  prometheus::Counter& rebuilds_;
  prometheus::Histogram& update_latency_;

  absl::Mutex& core_;  // held while stepping
  absl::Notification stopping_;

  absl::Mutex mu_;
  // By "run/slot@epoch".
  std::map<std::string, std::shared_ptr<Slot>> slots_ ABSL_GUARDED_BY(mu_);
  absl::Duration lease_duration_ ABSL_GUARDED_BY(mu_);  // set with the first slot taken
  // The learner leases whose holder said its run is complete, by lease name: slots not to take
  // while that learner holds the run (AcquireSlotRequest.complete_learners), which it does
  // while it evaluates the final policy, for as long as that takes (an image policy's, or a
  // CarRacing one's, can take many leases). Taking the run's slots meanwhile, every lease,
  // only to be told again, costs the coordinator transactions and the log a line each time. A
  // learner that dies before ending the run hands it to the next learner, at a new epoch, which
  // gets its slots. Each is forgotten some leases after it was said (kCompleteLearnerLeases):
  // by then its run has ended or, evaluated at length, is said complete once more.
  struct CompleteLearner {
    run::LeaseKey lease;
    absl::Time until;
  };
  std::map<std::string, CompleteLearner> complete_learners_ ABSL_GUARDED_BY(mu_);

  std::thread manager_;  // last: starts after everything above is initialised
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_ACTOR_SLOT_WORKERS_H_
