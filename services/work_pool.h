// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_WORK_POOL_H_
#define DCS_SERVICES_WORK_POOL_H_

// A fixed set of threads that run tasks from a bounded queue: where a service's gRPC reactions
// send the work that may block (the store's commits, runs' directories and checkpoints,
// decoding a rollout), so that gRPC's own threads never wait on a disk or a lock held across
// one. A full queue refuses the task at once (RESOURCE_EXHAUSTED) rather than blocking its
// caller: the caller is a reaction, which must not wait.
//
// Thread-safe. The destructor refuses new tasks, runs those already queued, then joins.

#include <cstddef>
#include <deque>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/functional/any_invocable.h"
#include "absl/status/status.h"
#include "absl/synchronization/mutex.h"

namespace dcs::services {

struct WorkPoolOptions {
  int threads = 4;
  size_t max_queued = 1024;  // tasks waiting for a thread, beyond those running
};

class WorkPool {
 public:
  using Task = absl::AnyInvocable<void() &&>;

  // REQUIRES: options.threads >= 1 and options.max_queued >= 1.
  explicit WorkPool(WorkPoolOptions options);
  ~WorkPool();
  WorkPool(const WorkPool&) = delete;
  WorkPool& operator=(const WorkPool&) = delete;

  // Queues `task` to run on one of the pool's threads. RESOURCE_EXHAUSTED, naming the limit,
  // if max_queued tasks wait already; UNAVAILABLE once the pool is being destroyed. A refused
  // task is not run (it is destroyed before this returns).
  absl::Status Schedule(Task task);

 private:
  void Work();

  const size_t max_queued_;
  absl::Mutex mu_;
  std::deque<Task> queued_ ABSL_GUARDED_BY(mu_);
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;
  std::vector<std::thread> threads_;  // started last, in the constructor
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_WORK_POOL_H_
