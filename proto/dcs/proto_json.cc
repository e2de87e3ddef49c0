// Copyright 2026 The DCS Authors.
#include "dcs/proto_json.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/json_util.h>
#include <google/protobuf/util/type_resolver.h>
#include <google/protobuf/util/type_resolver_util.h>

namespace dcs {
namespace {

constexpr char kTypeUrlPrefix[] = "type.googleapis.com";

// What MessageToJsonString does (the message's wire form, printed by its type), with the wire
// form serialized deterministically: map entries in key order.
std::string Print(const google::protobuf::Message& message, bool add_whitespace) {
  std::string wire;
  {
    google::protobuf::io::StringOutputStream stream(&wire);
    google::protobuf::io::CodedOutputStream coded(&stream);
    coded.SetSerializationDeterministic(true);
    message.SerializeToCodedStream(&coded);
  }
  // Built once and never destroyed; reading the generated pool is thread-safe.
  static google::protobuf::util::TypeResolver* const resolver =
      google::protobuf::util::NewTypeResolverForDescriptorPool(
          kTypeUrlPrefix, google::protobuf::DescriptorPool::generated_pool());
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  options.add_whitespace = add_whitespace;
  std::string json;
  // Printing fails only for Any fields whose type is unknown; DCS messages have none.
  (void)google::protobuf::util::BinaryToJsonString(
      resolver, std::string(kTypeUrlPrefix) + "/" + message.GetDescriptor()->full_name(), wire,
      &json, options);
  return json;
}

}  // namespace

std::string ProtoToJson(const google::protobuf::Message& message) {
  return Print(message, /*add_whitespace=*/true);
}

std::string ProtoToJsonLine(const google::protobuf::Message& message) {
  return Print(message, /*add_whitespace=*/false);
}

}  // namespace dcs
