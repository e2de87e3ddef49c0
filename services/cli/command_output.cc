// Copyright 2026 The DCS Authors.
#include "services/cli/command_output.h"

#include <google/protobuf/struct.pb.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "absl/strings/str_join.h"
#include "absl/strings/string_view.h"
#include "common/text_table.h"
#include "dcs/proto_json.h"
#include "report/gnuplot_figure.h"

namespace dcs::services::cli {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;

bool IsWellKnown(const Descriptor& message) {
  return absl::StartsWith(message.file()->name(), "google/protobuf/");
}

void RewriteMessage(const Descriptor& message, nlohmann::ordered_json& json);

// One value of `field` (an element, if it is repeated) in protobuf's JSON, rewritten as
// CommandJson says. A value the walk does not expect (an enum value this build does not know
// prints as its number) stays as it is.
void RewriteValue(const FieldDescriptor& field, nlohmann::ordered_json& value) {
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
    return RewriteMessage(*field.message_type(), value);
  }
  if (!value.is_string()) return;
  const std::string& text = value.get_ref<const std::string&>();
  int64_t signed_number = 0;
  uint64_t unsigned_number = 0;
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_INT64 &&
      absl::SimpleAtoi(text, &signed_number)) {
    value = signed_number;
  } else if (field.cpp_type() == FieldDescriptor::CPPTYPE_UINT64 &&
             absl::SimpleAtoi(text, &unsigned_number)) {
    value = unsigned_number;
  } else if (field.cpp_type() == FieldDescriptor::CPPTYPE_ENUM) {
    const google::protobuf::EnumValueDescriptor* enum_value =
        field.enum_type()->FindValueByName(text);
    if (enum_value != nullptr) value = EnumWord(*enum_value);
  }
}

// `json`, an object whose keys name `message`'s fields, rewritten field by field; a map's keys
// stay as they are.
void RewriteMessage(const Descriptor& message, nlohmann::ordered_json& json) {
  if (IsWellKnown(message) || !json.is_object()) return;
  for (auto& [key, value] : json.items()) {
    const FieldDescriptor* field = message.FindFieldByName(key);
    if (field == nullptr) continue;
    if (field->is_map()) {
      for (auto& entry : value) RewriteValue(*field->message_type()->map_value(), entry);
    } else if (field->is_repeated()) {
      for (auto& element : value) RewriteValue(*field, element);
    } else {
      RewriteValue(*field, value);
    }
  }
}

// A header's cell as a CSV column's or a JSON key's name: "LAST HEARTBEAT" -> "last_heartbeat".
std::string Key(absl::string_view header) {
  std::string key = absl::AsciiStrToLower(header);
  for (char& c : key) {
    if (!absl::ascii_isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return key;
}

}  // namespace

std::string EnumWord(const google::protobuf::EnumValueDescriptor& value) {
  const google::protobuf::EnumValueDescriptor* zero = value.type()->FindValueByNumber(0);
  absl::string_view prefix;
  if (zero != nullptr) prefix = zero->name();
  if (!absl::ConsumeSuffix(&prefix, "UNSPECIFIED")) prefix = "";
  return absl::AsciiStrToLower(absl::StripPrefix(value.name(), prefix));
}

std::string CommandJson(const google::protobuf::Message& message) {
  const std::string printed = ProtoToJsonLine(message);
  nlohmann::ordered_json json =
      nlohmann::ordered_json::parse(printed, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) return printed;  // protobuf prints JSON: not expected
  RewriteMessage(*message.GetDescriptor(), json);
  // Protobuf's strings are UTF-8; `replace` only keeps dump() from throwing if one were not.
  return json.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string FormatRows(const std::vector<std::vector<std::string>>& rows, OutputFormat format) {
  if (format == OutputFormat::kTable) return RenderTable(rows);
  if (rows.empty()) return "";
  std::vector<std::string> keys;
  for (const std::string& cell : rows[0]) keys.push_back(Key(cell));
  std::string text;
  if (format == OutputFormat::kCsv) {
    for (size_t i = 0; i < rows.size(); ++i) {
      absl::StrAppend(&text, absl::StrJoin(i == 0 ? keys : rows[i], ",",
                                           [](std::string* out, const std::string& cell) {
                                             absl::StrAppend(out, report::CsvField(cell));
                                           }),
                      "\n");
    }
    return text;
  }
  for (size_t i = 1; i < rows.size(); ++i) {
    google::protobuf::Struct row;
    for (size_t j = 0; j < rows[i].size() && j < keys.size(); ++j) {
      google::protobuf::Value& value = (*row.mutable_fields())[keys[j]];
      double number = 0;
      if (absl::SimpleAtod(rows[i][j], &number) && std::isfinite(number)) {
        value.set_number_value(number);
      } else {
        value.set_string_value(rows[i][j]);
      }
    }
    absl::StrAppend(&text, CommandJson(row), "\n");
  }
  return text;
}

}  // namespace dcs::services::cli
