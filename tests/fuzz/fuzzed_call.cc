// Copyright 2026 The DCS Authors.
#include "tests/fuzz/fuzzed_call.h"

#include <grpcpp/client_context.h>
#include <grpcpp/completion_queue.h>
#include <grpcpp/generic/generic_stub.h>
#include <grpcpp/support/byte_buffer.h>
#include <grpcpp/support/slice.h>

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"

namespace dcs::fuzz {
namespace {

// Waits for the one operation in flight on `queue`; returns whether it succeeded.
bool Await(grpc::CompletionQueue& queue) {
  void* tag = nullptr;
  bool ok = false;
  return queue.Next(&tag, &ok) && ok;
}

}  // namespace

FuzzedCall DecodeCall(const google::protobuf::ServiceDescriptor& service, absl::string_view input) {
  FuzzedCall call{.method = service.method(0)};
  if (input.empty()) return {.method = call.method, .requests = {""}};
  call.method = service.method(static_cast<unsigned char>(input[0]) % service.method_count());
  input.remove_prefix(1);
  if (!call.method->client_streaming()) {
    call.requests.emplace_back(input);
    return call;
  }
  while (input.size() >= 2) {
    const size_t length = static_cast<unsigned char>(input[0]) |
                          static_cast<size_t>(static_cast<unsigned char>(input[1])) << 8;
    input.remove_prefix(2);
    const size_t taken = std::min(length, input.size());
    call.requests.emplace_back(input.substr(0, taken));
    input.remove_prefix(taken);
  }
  return call;
}

std::string EncodeCall(const FuzzedCall& call) {
  std::string input(1, static_cast<char>(call.method->index()));
  if (!call.method->client_streaming()) return absl::StrCat(input, call.requests.at(0));
  for (const std::string& request : call.requests) {
    input.push_back(static_cast<char>(request.size() & 0xff));
    input.push_back(static_cast<char>(request.size() >> 8));
    input += request;
  }
  return input;
}

grpc::Status MakeCall(const std::shared_ptr<grpc::Channel>& channel, const FuzzedCall& call,
                      const std::string& token, absl::Duration timeout, int max_responses) {
  grpc::GenericStub stub(channel);
  grpc::ClientContext context;
  context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
  context.AddMetadata("authorization", absl::StrCat("Bearer ", token));
  grpc::CompletionQueue queue;
  // One operation in flight at a time, so the tag says nothing.
  void* const tag = &queue;
  const std::unique_ptr<grpc::GenericClientAsyncReaderWriter> stream = stub.PrepareCall(
      &context, absl::StrCat("/", call.method->service()->full_name(), "/", call.method->name()),
      &queue);
  stream->StartCall(tag);
  if (Await(queue)) {
    for (const std::string& request : call.requests) {
      grpc::Slice slice(request);
      const grpc::ByteBuffer buffer(&slice, 1);
      stream->Write(buffer, tag);
      if (!Await(queue)) break;  // the server ended the call: Finish says how
    }
    stream->WritesDone(tag);
    Await(queue);
    grpc::ByteBuffer response;
    int responses = 0;
    do {
      if (responses++ == max_responses) {
        context.TryCancel();
        break;
      }
      stream->Read(&response, tag);
    } while (Await(queue));
  }
  grpc::Status status;
  stream->Finish(&status, tag);
  Await(queue);
  queue.Shutdown();
  void* drained = nullptr;
  bool ok = false;
  while (queue.Next(&drained, &ok)) {
  }
  return status;
}

}  // namespace dcs::fuzz
