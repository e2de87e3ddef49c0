// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_COMMAND_OUTPUT_H_
#define DCS_SERVICES_CLI_COMMAND_OUTPUT_H_

// What `dcs` commands print as data: every `-o json` goes through CommandJson, so that scripts
// read the same spelling from every command. Thread-safe (pure functions).

#include <string>

#include <google/protobuf/descriptor.h>
#include <google/protobuf/generated_enum_reflection.h>
#include <google/protobuf/message.h>

namespace dcs::services::cli {

// An enum value as tables spell it: its name without the enum's prefix, in lower case
// ("SWEEP_STATE_COMPLETED" -> "completed", "SPLIT_OOD_LOW" -> "ood_low"). The prefix is what
// the enum's value 0 spells before "UNSPECIFIED", as every DCS enum names it.
std::string EnumWord(const google::protobuf::EnumValueDescriptor& value);

// EnumWord of a generated enum's value (EnumWordOf(v1::RUN_STATE_QUEUED) == "queued"); a value
// this build does not know, as its number.
template <typename E>
std::string EnumWordOf(E value) {
  const google::protobuf::EnumValueDescriptor* descriptor =
      google::protobuf::GetEnumDescriptor<E>()->FindValueByNumber(value);
  return descriptor == nullptr ? std::to_string(static_cast<int>(value)) : EnumWord(*descriptor);
}

// `message` as `-o json` prints it: protobuf's JSON mapping with the proto's field names
// (dcs/proto_json.h), indented, with two changes for scripts: 64-bit integers are numbers, not
// strings ("seed": 7), and enum values are their EnumWord ("state": "completed"). A map's keys
// stay strings, as JSON requires; well-known types (Timestamp, Duration, Struct) print as
// protobuf prints them. Not for files DCS reads back: protobuf's parser wants its own mapping.
std::string CommandJson(const google::protobuf::Message& message);

// As CommandJson, on one line without spaces: one record of a stream of them, one per line.
std::string CommandJsonLine(const google::protobuf::Message& message);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_COMMAND_OUTPUT_H_
