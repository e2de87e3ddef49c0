// Copyright 2026 The DCS Authors.
#include "services/coordinator/watchers.h"

#include <algorithm>
#include <cassert>
#include <utility>

namespace dcs::services {

Watchers::Watchers() : dispatcher_([this] { Dispatch(); }) {}

Watchers::~Watchers() {
  {
    absl::MutexLock lock(&mu_);
    assert(watchers_.empty());
    stopping_ = true;
  }
  dispatcher_.join();
}

int64_t Watchers::Add(std::vector<std::string> topics, absl::Duration min_interval, Look look,
                      Stop stop) {
  {
    absl::MutexLock lock(&mu_);
    if (!closed_) {
      const int64_t id = next_id_++;
      for (const std::string& topic : topics) followers_[topic].insert(id);
      Watcher& watcher = watchers_[id];
      watcher = {.topics = std::move(topics),
                 .min_interval = min_interval,
                 .look = std::move(look),
                 .stop = std::move(stop)};
      return id;
    }
  }
  stop();
  return 0;
}

void Watchers::Follow(int64_t id, std::vector<std::string> topics) {
  absl::MutexLock lock(&mu_);
  auto watcher = watchers_.find(id);
  if (watcher == watchers_.end() || watcher->second.topics == topics) return;
  Unfollow(id, watcher->second);
  for (const std::string& topic : topics) followers_[topic].insert(id);
  watcher->second.topics = std::move(topics);
}

void Watchers::Touch(int64_t id) {
  absl::MutexLock lock(&mu_);
  if (auto watcher = watchers_.find(id); watcher != watchers_.end()) MarkChanged(watcher->second);
}

void Watchers::Remove(int64_t id) {
  absl::MutexLock lock(&mu_);
  auto not_looking = [this, id]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) { return looking_ != id; };
  mu_.Await(absl::Condition(&not_looking));
  auto watcher = watchers_.find(id);
  if (watcher == watchers_.end()) return;
  Unfollow(id, watcher->second);
  watchers_.erase(watcher);
}

void Watchers::Notify(absl::string_view topic) {
  absl::MutexLock lock(&mu_);
  auto followers = followers_.find(topic);
  if (followers == followers_.end()) return;
  for (const int64_t id : followers->second) MarkChanged(watchers_.at(id));
}

void Watchers::NotifyAll() {
  absl::MutexLock lock(&mu_);
  for (auto& [id, watcher] : watchers_) MarkChanged(watcher);
}

void Watchers::Close() {
  // Under the lock, so that no watcher is removed (and gone) before its stop.
  absl::MutexLock lock(&mu_);
  closed_ = true;
  for (const auto& [id, watcher] : watchers_) watcher.stop();
}

int Watchers::size() const {
  absl::MutexLock lock(&mu_);
  return static_cast<int>(watchers_.size());
}

void Watchers::MarkChanged(Watcher& watcher) {
  watcher.changed = true;
  work_ = true;
}

void Watchers::Unfollow(int64_t id, const Watcher& watcher) {
  for (const std::string& topic : watcher.topics) {
    auto followers = followers_.find(topic);
    if (followers == followers_.end()) continue;
    followers->second.erase(id);
    if (followers->second.empty()) followers_.erase(followers);
  }
}

void Watchers::Dispatch() {
  mu_.Lock();
  while (!stopping_) {
    work_ = false;
    // The changed watcher that looked longest ago, if its interval is up; else when the first
    // interval is up.
    const absl::Time now = absl::Now();
    int64_t due = 0;
    absl::Time next = absl::InfiniteFuture();
    for (const auto& [id, watcher] : watchers_) {
      if (!watcher.changed) continue;
      const absl::Time at = watcher.last_look + watcher.min_interval;
      if (at > now) {
        next = std::min(next, at);
      } else if (due == 0 || watcher.last_look < watchers_.at(due).last_look) {
        due = id;
      }
    }
    if (due == 0) {
      auto woken = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) { return work_ || stopping_; };
      mu_.AwaitWithDeadline(absl::Condition(&woken), next);
      continue;
    }
    Watcher& watcher = watchers_.at(due);
    watcher.changed = false;
    watcher.last_look = now;
    const Look look = watcher.look;
    looking_ = due;
    mu_.Unlock();
    look();
    mu_.Lock();
    looking_ = 0;
  }
  mu_.Unlock();
}

}  // namespace dcs::services
