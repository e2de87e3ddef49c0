// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_SERVED_CALLS_H_
#define DCS_SERVICES_SERVED_CALLS_H_

// How every call of a DCS service starts, and where its work runs.
//
// Authentication in one place. Serve() checks the cluster's token (services/auth.h) before any
// of the service's code sees the call: a refused call gets a reactor that finishes at once,
// UNAUTHENTICATED, and is counted. Every handler of a service returns its reactor through
// Serve (or the unary shorthands built on it), so none has a check of its own to forget; the
// all-RPC refusal test (tests/integration/auth_test.cc) calls every method each process serves
// without the token. A streaming handler wraps its reactor the same way, whatever its kind:
//
//   return calls_.Serve<grpc::ServerWriteReactor<v1::RunEvent>>(
//       context, [&] { return new RunWatcher(...); });
//
// Reactions never block. gRPC runs handlers and reactions (OnReadDone, OnWriteDone, ...) on
// its own few threads; work that may wait (the store's commits, runs' directories and
// checkpoints, decoding a rollout) goes to the service's WorkPool instead (Offload, and
// Offloaded for a unary call), which finishes the call from its thread. Work on memory alone
// finishes inline (Inline). Calls that wait for work are parked (services/parked_calls.h).
//
// Thread-safe. Borrows the pool and the counter, which must outlive it.

#include <grpcpp/support/server_callback.h>
#include <grpcpp/server_context.h>

#include <utility>

#include "absl/status/status.h"
#include "services/auth.h"
#include "services/grpc_status.h"
#include "services/refusal_counter.h"
#include "services/work_pool.h"

namespace dcs::services {

class ServedCalls {
 public:
  // Counts every refusal (not OK) the unary shorthands finish with in `refusals`, and the
  // unauthenticated calls of every kind; null to count none.
  ServedCalls(WorkPool& pool, RefusalCounter* refusals) : pool_(pool), refusals_(refusals) {}

  // The call's reactor: `open()`'s if the call is authenticated, else one of the same kind
  // that finishes at once with UNAUTHENTICATED. `open` (Reactor*()) runs on this thread.
  template <typename Reactor, typename Open>
  Reactor* Serve(grpc::CallbackServerContext* context, Open open);

  // A unary call answered inline: `work` (absl::Status()) fills the response, its status
  // finishes the call. For work on memory only.
  template <typename Work>
  grpc::ServerUnaryReactor* Inline(grpc::CallbackServerContext* context, Work work);

  // A unary call answered from the pool: as Inline, but `work` runs on a pool thread. It must
  // hold what it reads by value or by pointer to the call's own request and response.
  template <typename Work>
  grpc::ServerUnaryReactor* Offloaded(grpc::CallbackServerContext* context, Work work);

  // Runs `work` on the pool and hands its result (absl::Status or StatusOr) to `done` there;
  // if the pool refuses it (full: RESOURCE_EXHAUSTED; stopping: UNAVAILABLE), `done` gets
  // that status at once, on this thread. `done` must be copyable.
  template <typename Work, typename Done>
  void Offload(Work work, Done done);

  // Finishes a unary call at once with `status`, counted: for an answer found inside Serve's
  // `open`.
  grpc::ServerUnaryReactor* Answer(grpc::CallbackServerContext* context,
                                   const absl::Status& status) {
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    Finish(reactor, status);
    return reactor;
  }

  // Counts `status` if it is a refusal (not OK).
  void Count(const absl::Status& status) {
    if (refusals_ != nullptr) refusals_->Count(status);
  }

 private:
  // Finishes a unary call with `status`, counted.
  void Finish(grpc::ServerUnaryReactor* reactor, const absl::Status& status) {
    Count(status);
    reactor->Finish(ToGrpcStatus(status));
  }

  WorkPool& pool_;
  RefusalCounter* const refusals_;  // may be null
};

// Implementation details.

template <typename Reactor, typename Open>
Reactor* ServedCalls::Serve(grpc::CallbackServerContext* context, Open open) {
  if (absl::Status refused = Authenticate(*context); !refused.ok()) {
    // Finishes at once; owned by gRPC until OnDone.
    class Refused final : public Reactor {
     public:
      explicit Refused(const absl::Status& status) { this->Finish(ToGrpcStatus(status)); }
      void OnDone() override { delete this; }
    };
    Count(refused);
    return new Refused(refused);
  }
  return open();
}

template <typename Work>
grpc::ServerUnaryReactor* ServedCalls::Inline(grpc::CallbackServerContext* context, Work work) {
  return Serve<grpc::ServerUnaryReactor>(context, [&] { return Answer(context, work()); });
}

template <typename Work>
grpc::ServerUnaryReactor* ServedCalls::Offloaded(grpc::CallbackServerContext* context,
                                                 Work work) {
  return Serve<grpc::ServerUnaryReactor>(context, [&] {
    grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
    Offload(std::move(work),
            [this, reactor](const absl::Status& status) { Finish(reactor, status); });
    return reactor;
  });
}

template <typename Work, typename Done>
void ServedCalls::Offload(Work work, Done done) {
  absl::Status scheduled =
      pool_.Schedule([work = std::move(work), done]() mutable { done(work()); });
  if (!scheduled.ok()) done(std::move(scheduled));
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_SERVED_CALLS_H_
