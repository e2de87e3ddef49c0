// Copyright 2026 The DCS Authors.
// Fuzzes the decoders of the data plane (services/trajectory_proto.h), what the learner's service
// and the actors decode from each other: a slot's rollout as LearnerService::PushRollout joins
// its pieces and decodes it (services/pieces.h, then SlotRolloutFromProto), and a policy as an
// actor decodes the weights GetSlotWork sends (PolicyFromBytes). The learner's service itself is
// not served here: its library links libtorch, whose headers clang 14 does not compile as C++20
// (tests/fuzz/README.md). The input's first byte picks the decoder (even: rollout, odd: policy);
// for a rollout the rest is the stream's PushRolloutRequest messages, each prefixed by its
// length as fuzzed_call.h frames them; for a policy, the serialised PolicyWeights. The seeds
// are valid messages (tests/fuzz/make_service_seeds.py).
// Asserts: every input decodes or gives INVALID_ARGUMENT (the header's error), or
// RESOURCE_EXHAUSTED for a stream over its limit; a rollout that decodes encodes and decodes
// again to the same message.

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "dcs/v1/learner_service.pb.h"
#include "dcs/v1/trajectory.pb.h"
#include "services/pieces.h"
#include "services/trajectory_proto.h"
#include "tests/fuzz/fuzz_check.h"

namespace dcs::fuzz {
namespace {

void CheckDecodeError(const absl::Status& status) {
  DCS_FUZZ_CHECK(
      status.ok() || absl::IsInvalidArgument(status) || absl::IsResourceExhausted(status), status);
}

// The stream's messages: each prefixed by its length (2 bytes, little-endian); a tail shorter
// than its length is the last message.
void FuzzRollout(absl::string_view input) {
  services::PieceJoiner<v1::PushRolloutRequest> joiner(&v1::PushRolloutRequest::mutable_data,
                                                       "the slot's rollout");
  while (input.size() >= 2) {
    const size_t length = static_cast<unsigned char>(input[0]) |
                          static_cast<size_t>(static_cast<unsigned char>(input[1])) << 8;
    input.remove_prefix(2);
    const absl::string_view bytes = input.substr(0, length);
    input.remove_prefix(bytes.size());
    v1::PushRolloutRequest piece;
    if (!piece.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) return;
    const absl::Status added = joiner.Add(std::move(piece));
    CheckDecodeError(added);
    if (!added.ok()) return;
  }
  if (!joiner.started()) return;  // PushRollout refuses an empty stream before decoding
  v1::SlotRollout proto;
  const absl::Status parsed = joiner.Parse(proto);
  CheckDecodeError(parsed);
  if (!parsed.ok()) return;
  const absl::StatusOr<actor::SlotRollout> rollout = services::SlotRolloutFromProto(proto);
  CheckDecodeError(rollout.status());
  if (!rollout.ok()) return;
  const v1::SlotRollout encoded = services::SlotRolloutToProto(*rollout);
  const absl::StatusOr<actor::SlotRollout> again = services::SlotRolloutFromProto(encoded);
  DCS_FUZZ_CHECK(again.ok(), again.status());
  DCS_FUZZ_CHECK(
      services::SlotRolloutToProto(*again).SerializeAsString() == encoded.SerializeAsString(),
      absl::OkStatus());
}

void FuzzPolicy(absl::string_view input) {
  CheckDecodeError(services::PolicyFromBytes(input).status());
}

}  // namespace
}  // namespace dcs::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const absl::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) {
    dcs::fuzz::FuzzRollout(rest);
  } else {
    dcs::fuzz::FuzzPolicy(rest);
  }
  return 0;
}
