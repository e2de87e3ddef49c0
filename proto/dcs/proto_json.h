// Copyright 2026 The DCS Authors.
#ifndef DCS_PROTO_JSON_H_
#define DCS_PROTO_JSON_H_

// DCS messages as the JSON that `-o json` prints and run directories hold: protobuf's JSON
// mapping with the proto's own snake_case field names, every field present (zeros too),
// indented. 64-bit integers are strings there, as the mapping requires. Thread-safe.

#include <string>

#include <google/protobuf/message.h>

namespace dcs {

std::string ProtoToJson(const google::protobuf::Message& message);

// The same JSON on one line (no newline in it, none after it): a line of a JSON Lines file.
std::string ProtoToJsonLine(const google::protobuf::Message& message);

}  // namespace dcs

#endif  // DCS_PROTO_JSON_H_
