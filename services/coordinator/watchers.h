// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_WATCHERS_H_
#define DCS_SERVICES_COORDINATOR_WATCHERS_H_

// Who watches what (WatchRun, WatchSweep), and when each looks again: a watcher follows topics
// (a run's, a sweep's) and looks (reads the store and sends what changed) only after a change
// of one of them, so an idle watcher costs nothing. Whoever changes the store says what it
// changed (Notify), or that it cannot say what (NotifyAll); each watcher of a changed topic
// then looks once, on the watchers' own thread: at once if it last looked at least its
// `min_interval` ago, else that long after its last look, so that a burst of changes costs one
// look at the latest state.
//
// Looks run one at a time, never under the lock, and never on the notifier's thread: a writer's
// Notify only marks watchers. Thread-safe. Watchers are added and removed by their owners
// (a watch call's reactor); Close tells every watcher, and each added later, to stop. The
// destructor joins the thread: every watcher must have been removed by then.

#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_map.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"

namespace dcs::services {

class Watchers {
 public:
  // Reads what the watcher shows and sends it if it changed; on the watchers' thread.
  using Look = std::function<void()>;
  // Ends the watch: the watchers close (the coordinator stops). On Close's caller's thread,
  // under the watchers' lock: it must not call this class.
  using Stop = std::function<void()>;

  Watchers();
  ~Watchers();
  Watchers(const Watchers&) = delete;
  Watchers& operator=(const Watchers&) = delete;

  // Adds a watcher of `topics`, to look at its first Touch or change, and then no sooner than
  // `min_interval` after its last look; returns its id. Once closed, calls `stop` at once
  // instead and returns 0 (which the other methods ignore).
  int64_t Add(std::vector<std::string> topics, absl::Duration min_interval, Look look,
              Stop stop);
  // The watcher now follows `topics` instead (a sweep's watcher follows its runs).
  void Follow(int64_t id, std::vector<std::string> topics);
  // The watcher looks again (after the interval), as if one of its topics changed: what it
  // saw changed while it could not send it.
  void Touch(int64_t id);
  // Removes the watcher; waits for its look to end if one runs, so that its callbacks may go
  // once this returns. REQUIRES: not called from the watcher's own look.
  void Remove(int64_t id);

  // Something under `topic` changed: its watchers look again.
  void Notify(absl::string_view topic);
  // Something changed and its writer cannot say what: every watcher looks again.
  void NotifyAll();

  // Calls every watcher's `stop`, and refuses watchers added later.
  void Close();

  // Watchers added and not removed.
  int size() const;

 private:
  struct Watcher {
    std::vector<std::string> topics;
    absl::Duration min_interval;
    Look look;
    Stop stop;
    bool changed = false;  // to look once the interval since its last look has passed
    absl::Time last_look = absl::InfinitePast();
  };

  void MarkChanged(Watcher& watcher) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);
  void Unfollow(int64_t id, const Watcher& watcher) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);
  void Dispatch();

  mutable absl::Mutex mu_;
  absl::flat_hash_map<int64_t, Watcher> watchers_ ABSL_GUARDED_BY(mu_);
  absl::flat_hash_map<std::string, absl::flat_hash_set<int64_t>> followers_ ABSL_GUARDED_BY(mu_);
  int64_t next_id_ ABSL_GUARDED_BY(mu_) = 1;
  int64_t looking_ ABSL_GUARDED_BY(mu_) = 0;  // the watcher whose look runs now; 0: none
  bool work_ ABSL_GUARDED_BY(mu_) = false;     // a watcher is marked changed
  bool closed_ ABSL_GUARDED_BY(mu_) = false;
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;  // the destructor runs
  std::thread dispatcher_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_WATCHERS_H_
