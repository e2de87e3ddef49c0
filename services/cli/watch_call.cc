// Copyright 2026 The DCS Authors.
#include "services/cli/watch_call.h"

#include <algorithm>

#include "absl/time/clock.h"

namespace dcs::services::cli::internal {
namespace {

// How often a watch asks whether its caller wants to stop.
constexpr absl::Duration kInterruptCheck = absl::Milliseconds(100);

}  // namespace

bool AwaitOperation(grpc::CompletionQueue& queue, grpc::ClientContext& context,
                    const std::function<bool()>& interrupted) {
  bool cancelled = false;
  while (true) {
    void* tag = nullptr;
    bool ok = false;
    switch (queue.AsyncNext(&tag, &ok, absl::ToChronoTime(absl::Now() + kInterruptCheck))) {
      case grpc::CompletionQueue::GOT_EVENT:
        return ok;
      case grpc::CompletionQueue::SHUTDOWN:
        return false;
      case grpc::CompletionQueue::TIMEOUT:
        if (!cancelled && interrupted()) {
          cancelled = true;
          context.TryCancel();
        }
        break;
    }
  }
}

bool SleepUnlessInterrupted(absl::Duration delay, const std::function<bool()>& interrupted) {
  for (const absl::Time end = absl::Now() + delay; absl::Now() < end;) {
    if (interrupted()) return false;
    absl::SleepFor(std::min(kInterruptCheck, end - absl::Now()));
  }
  return !interrupted();
}

}  // namespace dcs::services::cli::internal
