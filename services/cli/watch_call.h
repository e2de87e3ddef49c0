// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_WATCH_CALL_H_
#define DCS_SERVICES_CLI_WATCH_CALL_H_

// The client side of a watch (WatchRun, WatchSweep): one server stream, whose messages are the
// watched state now and then each change, read until the coordinator ends it with the state
// that ended; a stream broken by a coordinator that went away is opened again, with backoff,
// until it is back. The caller can stop it at any time (Ctrl-C). Thread-compatible: one watch
// per thread (gRPC stubs are thread-safe).

#include <grpcpp/client_context.h>
#include <grpcpp/completion_queue.h>
#include <grpcpp/support/async_stream.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "absl/random/random.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "common/status_util.h"
#include "services/backoff.h"
#include "services/grpc_status.h"
#include "services/unary_call.h"

namespace dcs::services::cli {

// What a watch tells its caller, and asks it.
template <typename Update>
struct WatchCallbacks {
  // The state now, then each change (the state again after the watch reconnected).
  std::function<void(const Update&)> on_update;
  // Checked every 100 ms: once true, the watch stops with CANCELLED (the work goes on).
  std::function<bool()> interrupted = [] { return false; };
  // The stream broke with a transient error (the coordinator restarts): said once per outage,
  // as the watch begins to reconnect (with backoff, until the coordinator is back).
  std::function<void(const absl::Status&)> on_lost = [](const absl::Status&) {};
};

// Watches with the call `start(stub, context, queue)` makes (a PrepareAsync method of the
// stub) until the stream ends OK; returns its last update. Watches again after a transient
// failure, or CANCELLED not of the caller's asking (a coordinator that stops cancels the calls
// it still holds). CANCELLED (`interrupted_message`) once interrupted; other errors annotated
// with `peer`.
template <typename Update, typename Stub, typename Start>
absl::StatusOr<Update> FollowWatch(Stub& stub, const Start& start,
                                   const WatchCallbacks<Update>& callbacks,
                                   const std::string& peer,
                                   const std::string& interrupted_message);

// Implementation details.

namespace internal {

// Between a watch's attempts to reach a coordinator that went away.
inline constexpr BackoffPolicy kWatchBackoff{.initial = absl::Milliseconds(250),
                                             .max = absl::Seconds(2)};

// Waits for the one operation in flight on `queue` and returns whether it succeeded; once
// `interrupted` says so (asked every 100 ms), cancels the call (its operations then fail).
bool AwaitOperation(grpc::CompletionQueue& queue, grpc::ClientContext& context,
                    const std::function<bool()>& interrupted);

// Sleeps for `delay`; returns false early if `interrupted` says so.
bool SleepUnlessInterrupted(absl::Duration delay, const std::function<bool()>& interrupted);

// One watch call read to its end (or cancelled once interrupted): each message to
// `on_update`. Returns the call's status.
template <typename Update, typename Stub, typename Start>
absl::Status ReadWatch(Stub& stub, const Start& start, const WatchCallbacks<Update>& callbacks,
                       const std::string& peer) {
  grpc::ClientContext context;
  grpc::CompletionQueue queue;
  auto await = [&] { return AwaitOperation(queue, context, callbacks.interrupted); };
  void* const tag = &queue;  // one operation in flight at a time: the tag says nothing
  std::unique_ptr<grpc::ClientAsyncReader<Update>> reader = start(stub, &context, &queue);
  reader->StartCall(tag);
  if (await()) {
    Update update;
    while (true) {
      reader->Read(&update, tag);
      if (!await()) break;
      callbacks.on_update(update);
    }
  }
  grpc::Status status;
  reader->Finish(&status, tag);
  await();
  queue.Shutdown();
  void* drained = nullptr;
  bool ok = false;
  while (queue.Next(&drained, &ok)) {
  }
  if (status.ok()) return absl::OkStatus();
  return Annotate(FromGrpcStatus(status), peer);
}

}  // namespace internal

template <typename Update, typename Stub, typename Start>
absl::StatusOr<Update> FollowWatch(Stub& stub, const Start& start,
                                   const WatchCallbacks<Update>& callbacks,
                                   const std::string& peer,
                                   const std::string& interrupted_message) {
  std::optional<Update> last;
  bool heard = false;  // an update came since the last failure
  const WatchCallbacks<Update> recorded{.on_update =
                                            [&](const Update& update) {
                                              last = update;
                                              heard = true;
                                              callbacks.on_update(update);
                                            },
                                        .interrupted = callbacks.interrupted,
                                        .on_lost = callbacks.on_lost};
  absl::BitGen random;
  int failures = 0;
  while (true) {
    const absl::Status status = internal::ReadWatch(stub, start, recorded, peer);
    if (status.ok()) {
      if (!last.has_value()) {
        return absl::InternalError(absl::StrCat(peer, " ended a watch without an update"));
      }
      return *std::move(last);
    }
    if (callbacks.interrupted()) return absl::CancelledError(interrupted_message);
    if (!IsTransient(status) && !absl::IsCancelled(status)) return status;
    if (std::exchange(heard, false)) failures = 0;
    if (failures++ == 0) callbacks.on_lost(status);
    if (!internal::SleepUnlessInterrupted(BackoffDelay(internal::kWatchBackoff, failures, random),
                                          callbacks.interrupted)) {
      return absl::CancelledError(interrupted_message);
    }
  }
}

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_WATCH_CALL_H_
