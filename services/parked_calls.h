// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_PARKED_CALLS_H_
#define DCS_SERVICES_PARKED_CALLS_H_

// Long polls: calls that found nothing to hand out, held by the server until what they wait for
// may have changed, or their time is up. A worker that asks the coordinator for work and finds
// none waits there (up to the `wait` its request names) instead of asking again a poll interval
// later: new work reaches it at once (an evaluation's jobs the moment the learner submits them),
// and an idle worker costs at most one attempt per `wait` (none while its question is known to
// have no answer, below).
//
// A call parks under a topic (what it waits for: "evaluation jobs", one evaluation's results)
// with an attempt and an expiry. The attempt runs at once, then again whenever Wake(topic) is
// called: an attempt that finishes its call (it found something, or failed) returns true and the
// call is dropped; one that finds nothing returns false and the call stays parked. A call whose
// deadline passes is expired instead: the expiry finishes it with its empty answer. A wake that
// comes while an attempt runs makes the call try again after it, so no change is missed.
// Attempts and expiries run on the parked calls' own thread, one at a time, never under a lock;
// each call ends in exactly one successful attempt or one expiry.
//
// Asking costs the attempts that can find something, not one per parked call. Calls may name
// the question they ask (AcquireSlot's: a free slot for these numerics): calls of one topic and
// one question find the same in the same state, whoever asks. Once one of them finds nothing,
// the question is known to have no answer until its topic is woken: the rest of its calls are
// not tried, and a call that parks with it is not tried when it parks. So work must come with
// a wake of its topic: whatever makes work (a run queued, a slot freed, a lease lapsed) wakes
// the calls that wait for it. Thousands of idle workers parked on one topic cost a wake one
// attempt per question, plus one per call it satisfies, and cost nothing when they park.
//
// Thread-safe. The destructor expires every call still parked, then joins its thread.

#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"

namespace dcs::services {

class ParkedCalls {
 public:
  // Tries the call again; true once it has finished the call.
  using Attempt = std::function<bool()>;
  // Finishes the call with nothing.
  using Expire = std::function<void()>;

  ParkedCalls();
  ~ParkedCalls();
  ParkedCalls(const ParkedCalls&) = delete;
  ParkedCalls& operator=(const ParkedCalls&) = delete;

  // Parks a call until `deadline` under `topic`, and makes its first attempt. `question` names
  // what the attempt asks, the same for calls that find the same in the same state; empty if
  // the call's question is its own.
  void Park(std::string topic, std::string question, absl::Time deadline, Attempt attempt,
            Expire expire);

  // Something the calls parked under `topic` wait for may have changed: they try again.
  void Wake(absl::string_view topic);

 private:
  struct Call {
    std::string topic;
    std::string question;  // empty: the call's own
    int64_t parked;        // when, in the order of Park calls
    absl::Time deadline;
    Attempt attempt;
    Expire expire;
    bool woken = false;  // to attempt at the next round
  };

  void Dispatch();

  absl::Mutex mu_;
  std::vector<Call> parked_ ABSL_GUARDED_BY(mu_);
  // Topics woken while their calls were out of parked_, attempting.
  absl::flat_hash_set<std::string> woken_while_out_ ABSL_GUARDED_BY(mu_);
  // The questions (topic, question) an attempt found nothing for since their topic's last wake.
  absl::flat_hash_set<std::pair<std::string, std::string>> unanswered_ ABSL_GUARDED_BY(mu_);
  int64_t parks_ ABSL_GUARDED_BY(mu_) = 0;
  bool work_ ABSL_GUARDED_BY(mu_) = false;        // a call in parked_ is woken
  bool attempting_ ABSL_GUARDED_BY(mu_) = false;  // a round's calls are out of parked_
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;
  std::thread dispatcher_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_PARKED_CALLS_H_
