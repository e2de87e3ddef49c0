// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_FUZZ_FUZZED_CALL_H_
#define DCS_TESTS_FUZZ_FUZZED_CALL_H_

// A call of a gRPC service's method, described by a fuzz input, made as a client makes it: the
// service fuzzers' one driver. The input's first byte picks the method (its index in the
// service's descriptor, modulo their number); the rest is the request's bytes, or for a
// client-streaming method the requests', each prefixed by its length (2 bytes, little-endian;
// a tail shorter than its length is the last request). The bytes go on the wire as they are:
// the server parses them, as it parses what any client sends. Thread-compatible.

#include <grpcpp/channel.h>
#include <grpcpp/support/status.h>
#include <google/protobuf/descriptor.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "absl/strings/string_view.h"
#include "absl/time/time.h"

namespace dcs::fuzz {

struct FuzzedCall {
  const google::protobuf::MethodDescriptor* method;  // of the service; never null
  std::vector<std::string> requests;                 // one, unless the method streams its requests
};

// The call `input` describes (above). REQUIRES: `service` has a method.
FuzzedCall DecodeCall(const google::protobuf::ServiceDescriptor& service, absl::string_view input);

// The input that describes `call`: what seeds are written with.
std::string EncodeCall(const FuzzedCall& call);

// Makes `call` on `channel` with the bearer `token`, within `timeout`: writes its requests,
// closes its side, reads every response, or cancels the call after `max_responses` of them
// (for a stream that ends only when what it watches does). Returns the call's status.
grpc::Status MakeCall(const std::shared_ptr<grpc::Channel>& channel, const FuzzedCall& call,
                      const std::string& token, absl::Duration timeout,
                      int max_responses = std::numeric_limits<int>::max());

}  // namespace dcs::fuzz

#endif  // DCS_TESTS_FUZZ_FUZZED_CALL_H_
