// Copyright 2026 The DCS Authors.
#include "services/parked_calls.h"

#include <algorithm>
#include <string>
#include <utility>

namespace dcs::services {

ParkedCalls::ParkedCalls() : dispatcher_([this] { Dispatch(); }) {}

ParkedCalls::~ParkedCalls() {
  {
    absl::MutexLock lock(&mu_);
    stopping_ = true;
  }
  dispatcher_.join();
}

void ParkedCalls::Park(std::string topic, std::string question, absl::Time deadline,
                       Attempt attempt, Expire expire) {
  {
    absl::MutexLock lock(&mu_);
    if (!stopping_) {
      // Not tried while its question is known to have no answer.
      const bool woken =
          question.empty() || !unanswered_.contains(std::pair(topic, question));
      parked_.push_back({.topic = std::move(topic),
                         .question = std::move(question),
                         .parked = parks_++,
                         .deadline = deadline,
                         .attempt = std::move(attempt),
                         .expire = std::move(expire),
                         .woken = woken});
      work_ = true;  // attempts it, or waits for its deadline too
      return;
    }
  }
  expire();  // the server is stopping: no wait
}

void ParkedCalls::Wake(absl::string_view topic) {
  absl::MutexLock lock(&mu_);
  for (Call& call : parked_) {
    if (call.topic == topic) {
      call.woken = true;
      work_ = true;
    }
  }
  absl::erase_if(unanswered_, [&](const auto& asked) { return asked.first == topic; });
  if (attempting_) woken_while_out_.emplace(topic);
}

void ParkedCalls::Dispatch() {
  mu_.Lock();
  while (true) {
    absl::Time next = absl::InfiniteFuture();
    for (const Call& call : parked_) next = std::min(next, call.deadline);
    auto ready = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) { return work_ || stopping_; };
    mu_.AwaitWithDeadline(absl::Condition(&ready), next);
    const bool stopping = stopping_;
    const absl::Time now = absl::Now();
    // The calls woken or due, out of parked_ while they are attempted or expired.
    const auto stays = std::partition(parked_.begin(), parked_.end(), [&](const Call& call) {
      return !stopping && !call.woken && call.deadline > now;
    });
    std::vector<Call> out(std::make_move_iterator(stays), std::make_move_iterator(parked_.end()));
    parked_.erase(stays, parked_.end());
    // The longest parked first: of calls that ask the same, it is the one served.
    std::ranges::sort(out, {}, &Call::parked);
    work_ = false;
    attempting_ = true;
    mu_.Unlock();

    std::vector<Call> unfinished;
    // The questions this round's attempts found nothing for.
    absl::flat_hash_set<std::pair<std::string, std::string>> unanswered;
    for (Call& call : out) {
      if (!stopping && call.woken) {
        const bool asked = !call.question.empty();
        if (!asked || !unanswered.contains(std::pair(call.topic, call.question))) {
          if (call.attempt()) continue;  // finished
          if (asked) unanswered.emplace(call.topic, call.question);
        }
      }
      if (stopping || absl::Now() >= call.deadline) {
        call.expire();
        continue;
      }
      unfinished.push_back(std::move(call));
    }

    mu_.Lock();
    attempting_ = false;
    // Unanswered until their topic's next wake, unless it came during the round.
    for (const auto& asked : unanswered) {
      if (!woken_while_out_.contains(asked.first)) unanswered_.insert(asked);
    }
    for (Call& call : unfinished) {
      call.woken = woken_while_out_.contains(call.topic);
      work_ = work_ || call.woken;
      parked_.push_back(std::move(call));
    }
    woken_while_out_.clear();
    if (stopping) break;
  }
  mu_.Unlock();
}

}  // namespace dcs::services
