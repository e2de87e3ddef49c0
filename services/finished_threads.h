// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_FINISHED_THREADS_H_
#define DCS_SERVICES_FINISHED_THREADS_H_

// Work items that each run on a thread of their own (a learner's hosted runs, an actor's
// slots), kept in a map of shared pointers; an item says it is finished by setting its `done`
// as its thread's last act. Thread-safe under the map's mutex.

#include <memory>
#include <vector>

#include "absl/synchronization/mutex.h"

namespace dcs::services {

// Removes the finished items from `items` (guarded by `mu`) and joins their threads, outside
// the lock.
template <typename Map>
void JoinFinished(absl::Mutex& mu, Map& items) {
  std::vector<typename Map::mapped_type> finished;
  {
    absl::MutexLock lock(&mu);
    for (auto it = items.begin(); it != items.end();) {
      if (it->second->done) {
        finished.push_back(std::move(it->second));
        it = items.erase(it);
      } else {
        ++it;
      }
    }
  }
  for (const typename Map::mapped_type& item : finished) item->thread.join();
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_FINISHED_THREADS_H_
