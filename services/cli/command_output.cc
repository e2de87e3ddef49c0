// Copyright 2026 The DCS Authors.
#include "services/cli/command_output.h"

#include <google/protobuf/struct.pb.h>

#include <algorithm>
#include <cmath>
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

bool Is64BitInteger(const FieldDescriptor& field) {
  return field.cpp_type() == FieldDescriptor::CPPTYPE_INT64 ||
         field.cpp_type() == FieldDescriptor::CPPTYPE_UINT64;
}

bool IsWellKnown(const Descriptor& message) {
  return absl::StartsWith(message.file()->name(), "google/protobuf/");
}

// Copies protobuf's JSON of a message to `out_`, rewriting the values CommandJson names. The
// input is the printer's own output, so it is well formed; a value the walk does not expect
// (an enum value this build does not know prints as its number) is copied as it is.
class JsonRewriter {
 public:
  explicit JsonRewriter(absl::string_view json) : in_(json) {}

  std::string Rewrite(const Descriptor& message) {
    Message(message);
    absl::StrAppend(&out_, in_.substr(pos_));
    return std::move(out_);
  }

 private:
  char Peek() const { return pos_ < in_.size() ? in_[pos_] : '\0'; }
  void Put() { out_.push_back(in_[pos_++]); }

  void CopyWhitespace() {
    while (pos_ < in_.size() && absl::ascii_isspace(static_cast<unsigned char>(in_[pos_]))) Put();
  }

  // Reads the string token at pos_ and returns it whole, quotes included.
  absl::string_view ReadString() {
    const size_t start = pos_++;
    while (pos_ < in_.size() && in_[pos_] != '"') pos_ += in_[pos_] == '\\' ? 2 : 1;
    pos_ = std::min(pos_ + 1, in_.size());
    return in_.substr(start, pos_ - start);
  }

  // Copies the object or array at pos_, calling `value(key)` to copy each entry's value (`key`:
  // an object entry's key without its quotes; empty in an array). Copies any other value as it
  // is.
  template <typename ValueFunction>
  void Container(ValueFunction value) {
    if (Peek() == '"') {
      absl::StrAppend(&out_, ReadString());
      return;
    }
    if (Peek() != '{' && Peek() != '[') {
      while (pos_ < in_.size() && !absl::StrContains(",}] \n", in_[pos_])) Put();
      return;
    }
    const char close = Peek() == '{' ? '}' : ']';
    Put();
    for (CopyWhitespace(); pos_ < in_.size() && Peek() != close; CopyWhitespace()) {
      const size_t start = pos_;
      absl::string_view key;
      if (close == '}') {
        key = ReadString();
        absl::StrAppend(&out_, key);
        key = key.substr(1, key.size() - 2);
        CopyWhitespace();
        if (Peek() == ':') Put();
        CopyWhitespace();
      }
      value(key);
      CopyWhitespace();
      if (Peek() == ',' || pos_ == start) Put();  // (the second: never stuck on a stray byte)
    }
    if (pos_ < in_.size()) Put();
  }

  void CopyValue() {
    Container([this](absl::string_view) { CopyValue(); });
  }

  // An object whose keys name `message`'s fields.
  void Message(const Descriptor& message) {
    if (IsWellKnown(message)) return CopyValue();
    Container([this, &message](absl::string_view key) {
      const FieldDescriptor* field = message.FindFieldByName(std::string(key));
      if (field == nullptr) {
        CopyValue();
      } else if (field->is_map()) {  // keys stay as they are
        const FieldDescriptor& value = *field->message_type()->map_value();
        Container([this, &value](absl::string_view) { Single(value); });
      } else if (field->is_repeated()) {
        Container([this, field](absl::string_view) { Single(*field); });
      } else {
        Single(*field);
      }
    });
  }

  // One value of `field` (an element, if it is repeated).
  void Single(const FieldDescriptor& field) {
    if (field.cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) return Message(*field.message_type());
    if (Peek() != '"') return CopyValue();
    const absl::string_view text = ReadString();
    const std::string inner(text.substr(1, text.size() - 2));
    const google::protobuf::EnumValueDescriptor* enum_value =
        field.cpp_type() == FieldDescriptor::CPPTYPE_ENUM
            ? field.enum_type()->FindValueByName(inner)
            : nullptr;
    if (Is64BitInteger(field)) {
      absl::StrAppend(&out_, inner);  // the printer writes the number's decimal digits
    } else if (enum_value != nullptr) {
      absl::StrAppend(&out_, "\"", EnumWord(*enum_value), "\"");
    } else {
      absl::StrAppend(&out_, text);
    }
  }

  absl::string_view in_;
  size_t pos_ = 0;
  std::string out_;
};

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
  return JsonRewriter(ProtoToJsonLine(message)).Rewrite(*message.GetDescriptor());
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
