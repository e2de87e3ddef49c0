// Copyright 2026 The DCS Authors.
#ifndef DCS_PROTO_JSON_H_
#define DCS_PROTO_JSON_H_

// DCS messages as JSON: protobuf's JSON mapping with the proto's own snake_case field names,
// every field present (zeros too). 64-bit integers are strings there, as the mapping requires.
// A map's entries are in key order, so the same message prints the same JSON every time
// (MessageToJsonString prints them in the order of the map's hash, which varies between
// processes). Thread-safe.

#include <string>

#include <google/protobuf/message.h>

namespace dcs {

// Indented: what `-o json` prints and run directories hold.
std::string ProtoToJson(const google::protobuf::Message& message);

// On one line, without spaces: one record of a stream of them, one per line.
std::string ProtoToJsonLine(const google::protobuf::Message& message);

}  // namespace dcs

#endif  // DCS_PROTO_JSON_H_
