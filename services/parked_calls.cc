// Copyright 2026 The DCS Authors.
#include "services/parked_calls.h"

#include <algorithm>
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

void ParkedCalls::Park(std::string topic, absl::Time deadline, Attempt attempt, Expire expire) {
  {
    absl::MutexLock lock(&mu_);
    if (!stopping_) {
      parked_.push_back({.topic = std::move(topic),
                         .deadline = deadline,
                         .attempt = std::move(attempt),
                         .expire = std::move(expire),
                         .woken = true});
      work_ = true;
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
    work_ = false;
    attempting_ = true;
    mu_.Unlock();

    std::vector<Call> unfinished;
    for (Call& call : out) {
      if (!stopping && call.woken && call.attempt()) continue;  // finished
      if (stopping || absl::Now() >= call.deadline) {
        call.expire();
        continue;
      }
      unfinished.push_back(std::move(call));
    }

    mu_.Lock();
    attempting_ = false;
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
