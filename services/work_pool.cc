// Copyright 2026 The DCS Authors.
#include "services/work_pool.h"

#include <cassert>
#include <utility>

#include "absl/strings/str_cat.h"

namespace dcs::services {

WorkPool::WorkPool(WorkPoolOptions options) : max_queued_(options.max_queued) {
  assert(options.threads >= 1 && options.max_queued >= 1);
  threads_.reserve(options.threads);
  for (int i = 0; i < options.threads; ++i) threads_.emplace_back([this] { Work(); });
}

WorkPool::~WorkPool() {
  {
    absl::MutexLock lock(&mu_);
    stopping_ = true;
  }
  for (std::thread& thread : threads_) thread.join();
}

absl::Status WorkPool::Schedule(Task task) {
  absl::MutexLock lock(&mu_);
  if (stopping_) return absl::UnavailableError("the server is stopping");
  if (queued_.size() >= max_queued_) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "the server is overloaded: ", max_queued_, " calls wait for a thread already"));
  }
  queued_.push_back(std::move(task));
  return absl::OkStatus();
}

void WorkPool::Work() {
  while (true) {
    Task task;
    {
      absl::MutexLock lock(&mu_);
      auto has_work = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
        return !queued_.empty() || stopping_;
      };
      mu_.Await(absl::Condition(&has_work));
      if (queued_.empty()) return;  // stopping, and everything queued has run
      task = std::move(queued_.front());
      queued_.pop_front();
    }
    std::move(task)();
  }
}

}  // namespace dcs::services
