// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_COMMAND_OUTPUT_H_
#define DCS_SERVICES_CLI_COMMAND_OUTPUT_H_

// What `dcs` commands print as data, in the format of `-o`: a table for people, CSV, or JSON
// Lines for scripts (each line of stdout one JSON value). Every JSON line goes through
// CommandJson, so that scripts read the same spelling from every command. Thread-safe
// (constant data, pure functions).

#include <string>
#include <vector>

#include <google/protobuf/descriptor.h>
#include <google/protobuf/generated_enum_reflection.h>
#include <google/protobuf/message.h>

#include "common/enum_names.h"

namespace dcs::services::cli {

enum class OutputFormat { kTable, kJson, kCsv };
inline constexpr EnumName<OutputFormat> kOutputFormatNames[] = {
    {OutputFormat::kTable, "table"}, {OutputFormat::kJson, "json"}, {OutputFormat::kCsv, "csv"}};
static_assert(InEnumOrder(kOutputFormatNames));

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

// `message` as `-o json` prints it, on one line: protobuf's JSON mapping with the proto's field
// names (dcs/proto_json.h ProtoToJsonLine), with two changes for scripts: 64-bit integers are
// numbers, not strings ("seed":7), and enum values are their EnumWord ("state":"completed"). A
// map's keys stay strings, as JSON requires; well-known types (Timestamp, Duration, Struct)
// print as protobuf prints them. Not for files DCS reads back: protobuf's parser wants its own
// mapping.
std::string CommandJson(const google::protobuf::Message& message);

// `rows` (the header first) in `format`, each line ending in a newline: a table
// (common/text_table.h); CSV; or JSON Lines, an object per row after the header. CSV's header
// and JSON's keys are the header's cells in lower case, other than letters and digits as '_'
// ("STEPS/S" -> "steps_s"); in JSON a cell that reads as a finite number is a number.
std::string FormatRows(const std::vector<std::vector<std::string>>& rows, OutputFormat format);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_COMMAND_OUTPUT_H_
