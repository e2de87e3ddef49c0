// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_UNARY_CALL_H_
#define DCS_SERVICES_UNARY_CALL_H_

// One unary call with a deadline, its status as an absl::Status (annotated with the peer's
// name): the client side of every worker-to-coordinator, actor-to-learner and client call;
// which failures are worth the same call again, and which mean a lease is lost; and the call
// retried with backoff until it succeeds or the caller gives up. Thread-safe (gRPC stubs are).

#include <grpcpp/client_context.h>
#include <grpcpp/support/status.h>

#include "absl/random/random.h"
#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/status_util.h"
#include "services/backoff.h"
#include "services/channel.h"
#include "services/grpc_status.h"

namespace dcs::services {

// The peer is down, restarting or slow, rather than refusing: the same call may succeed later.
inline bool IsTransient(const absl::Status& status) {
  return absl::IsUnavailable(status) || absl::IsDeadlineExceeded(status);
}

// The coordinator refuses a call made under a lease that is no longer the caller's: the lease
// moved to another holder or lapsed (FAILED_PRECONDITION), or its run is gone (NOT_FOUND).
inline bool IsLeaseLost(const absl::Status& status) {
  return absl::IsFailedPrecondition(status) || absl::IsNotFound(status);
}

template <typename Stub, typename Request, typename Response>
absl::Status CallUnary(Stub& stub,
                       grpc::Status (Stub::*method)(grpc::ClientContext*, const Request&,
                                                    Response*),
                       const Request& request, Response& response, absl::Duration timeout,
                       absl::string_view peer) {
  grpc::ClientContext context;
  SetTimeout(context, timeout);
  const grpc::Status status = (stub.*method)(&context, request, &response);
  if (status.ok()) return absl::OkStatus();
  return Annotate(FromGrpcStatus(status), peer);
}

// Makes `attempt` (a call: absl::Status()) until it succeeds or fails for good (not
// IsTransient), or until `keep_trying(status)` returns false after a transient failure; backs
// off by `backoff` between attempts. Returns the last status.
template <typename Attempt, typename KeepTrying>
absl::Status RetryTransient(Attempt attempt, const BackoffPolicy& backoff,
                            KeepTrying keep_trying) {
  absl::BitGen random;
  for (int number = 1;; ++number) {
    const absl::Status status = attempt();
    if (status.ok() || !IsTransient(status) || !keep_trying(status)) return status;
    absl::SleepFor(BackoffDelay(backoff, number, random));
  }
}

// CallUnary, retried as RetryTransient retries.
template <typename Stub, typename Request, typename Response, typename KeepTrying>
absl::Status CallWithRetries(Stub& stub,
                             grpc::Status (Stub::*method)(grpc::ClientContext*, const Request&,
                                                          Response*),
                             const Request& request, Response& response, absl::Duration timeout,
                             absl::string_view peer, const BackoffPolicy& backoff,
                             KeepTrying keep_trying) {
  return RetryTransient(
      [&] { return CallUnary(stub, method, request, response, timeout, peer); }, backoff,
      keep_trying);
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_UNARY_CALL_H_
