// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_STREAM_CALL_H_
#define DCS_SERVICES_STREAM_CALL_H_

// The client side of the streaming calls (checkpoints, run files, policies and rollouts travel
// in pieces: services/pieces.h): one call with a deadline over a sync stub, its status as an
// absl::Status annotated with the peer's name, as CallUnary (services/unary_call.h) does for
// unary calls. Thread-safe (gRPC stubs are).

#include <grpcpp/client_context.h>
#include <grpcpp/support/sync_stream.h>

#include <memory>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"
#include "absl/time/time.h"
#include "common/status_util.h"
#include "services/channel.h"
#include "services/grpc_status.h"
#include "services/unary_call.h"

namespace dcs::services {

// Writes `requests` in order on a client stream, then returns the call's status.
template <typename Stub, typename Request, typename Response>
absl::Status CallClientStream(Stub& stub,
                              std::unique_ptr<grpc::ClientWriter<Request>> (Stub::*method)(
                                  grpc::ClientContext*, Response*),
                              const std::vector<Request>& requests, Response& response,
                              absl::Duration timeout, absl::string_view peer) {
  grpc::ClientContext context;
  SetTimeout(context, timeout);
  std::unique_ptr<grpc::ClientWriter<Request>> writer = (stub.*method)(&context, &response);
  for (const Request& request : requests) {
    if (!writer->Write(request)) break;  // the stream broke: Finish says why
  }
  writer->WritesDone();
  const grpc::Status status = writer->Finish();
  if (status.ok()) return absl::OkStatus();
  return Annotate(FromGrpcStatus(status), peer);
}

// CallClientStream, retried as RetryTransient retries: the whole stream again.
template <typename Stub, typename Request, typename Response, typename KeepTrying>
absl::Status CallClientStreamWithRetries(
    Stub& stub,
    std::unique_ptr<grpc::ClientWriter<Request>> (Stub::*method)(grpc::ClientContext*,
                                                                 Response*),
    const std::vector<Request>& requests, Response& response, absl::Duration timeout,
    absl::string_view peer, const BackoffPolicy& backoff, KeepTrying keep_trying) {
  return RetryTransient(
      [&] { return CallClientStream(stub, method, requests, response, timeout, peer); },
      backoff, keep_trying);
}

// Hands every message of a server stream to `on_message`, in order; an error it returns ends
// the call with that error. Returns the call's status otherwise.
template <typename Stub, typename Request, typename Message, typename OnMessage>
absl::Status CallServerStream(Stub& stub,
                              std::unique_ptr<grpc::ClientReader<Message>> (Stub::*method)(
                                  grpc::ClientContext*, const Request&),
                              const Request& request, absl::Duration timeout,
                              absl::string_view peer, OnMessage on_message) {
  grpc::ClientContext context;
  SetTimeout(context, timeout);
  std::unique_ptr<grpc::ClientReader<Message>> reader = (stub.*method)(&context, request);
  Message message;
  while (reader->Read(&message)) {
    if (absl::Status taken = on_message(message); !taken.ok()) {
      context.TryCancel();
      reader->Finish().ok();  // drains the call; the error is ours
      return taken;
    }
  }
  const grpc::Status status = reader->Finish();
  if (status.ok()) return absl::OkStatus();
  return Annotate(FromGrpcStatus(status), peer);
}

}  // namespace dcs::services

#endif  // DCS_SERVICES_STREAM_CALL_H_
