// Copyright 2026 The DCS Authors.
#include "common/worker_info.h"

namespace dcs {

absl::string_view WorkerRoleName(WorkerRole role) {
  switch (role) {
    case WorkerRole::kLearner: return "learner";
    case WorkerRole::kActor: return "actor";
  }
  return "unknown";
}

}  // namespace dcs
