// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_WORKER_INFO_H_
#define DCS_COMMON_WORKER_INFO_H_

// What a worker (a learner or an actor process) says about itself when it registers with the
// coordinator. Plain data; thread-safe (pure functions).

#include <cstdint>
#include <string>
#include <vector>

#include "absl/strings/string_view.h"
#include "common/library_version.h"

namespace dcs {

enum class WorkerRole { kLearner, kActor };

// "learner" or "actor".
absl::string_view WorkerRoleName(WorkerRole role);

// What a worker says about itself when it registers.
struct WorkerInfo {
  WorkerRole role = WorkerRole::kActor;
  std::string address;  // host:port of the worker's own gRPC server
  std::string hostname;
  int64_t pid = 0;
  std::string version;  // DCS build, e.g. "0.1.0+3f2a9c1"
  std::vector<LibraryVersion> libraries;
};

}  // namespace dcs

#endif  // DCS_COMMON_WORKER_INFO_H_
