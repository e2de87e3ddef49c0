// Copyright 2026 The DCS Authors.
#include "dcs/proto_json.h"

#include <google/protobuf/util/json_util.h>

namespace dcs {
namespace {

std::string Print(const google::protobuf::Message& message, bool indented) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  options.add_whitespace = indented;
  std::string json;
  // Printing fails only for Any fields whose type is unknown; DCS messages have none.
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json;
}

}  // namespace

std::string ProtoToJson(const google::protobuf::Message& message) { return Print(message, true); }

std::string ProtoToJsonLine(const google::protobuf::Message& message) {
  return Print(message, false);
}

}  // namespace dcs
