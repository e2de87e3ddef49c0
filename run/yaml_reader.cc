// Copyright 2026 The DCS Authors.
#include "run/yaml_reader.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <type_traits>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"

namespace dcs::run {
namespace {

constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53

// The number a plain scalar's text is (finite or not), or nullopt.
std::optional<double> ParseNumber(absl::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// A scalar with no quotes and no tag, or with a core-schema tag for a number or boolean.
bool IsPlain(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float" ||
         tag == "tag:yaml.org,2002:bool";
}

}  // namespace

absl::StatusOr<YAML::Node> YamlReader::Load(absl::string_view text) const {
  try {
    return YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    return absl::InvalidArgumentError(absl::StrCat(where_, ": line ", e.mark.line + 1,
                                                   ", column ", e.mark.column + 1, ": ", e.msg));
  }
}

absl::Status YamlReader::Error(absl::string_view path, const YAML::Node& node,
                               absl::string_view message) const {
  const YAML::Mark mark = node.Mark();
  const std::string shown = Shown(path);
  return absl::InvalidArgumentError(
      absl::StrCat(where_, ": ", shown, shown.empty() ? "" : ": ",
                   mark.is_null() ? "" : absl::StrCat("line ", mark.line + 1, ": "), message));
}

void YamlReader::Note(const std::string& path, const YAML::Node& node) {
  if (!node.Mark().is_null()) lines_[path] = node.Mark().line + 1;
}

std::string YamlReader::Shown(absl::string_view path) const {
  return shown_path_ ? shown_path_(path) : std::string(path);
}

absl::Status YamlReader::ForEachKey(const YAML::Node& node, absl::string_view path,
                                    absl::Span<const absl::string_view> allowed,
                                    ReadEntry read) {
  return ForEachKeyOf(node, path, allowed, read);
}

absl::Status YamlReader::ForEachEntry(const YAML::Node& node, absl::string_view path,
                                      ReadEntry read) {
  return ForEachKeyOf(node, path, std::nullopt, read);
}

absl::Status YamlReader::ForEachKeyOf(const YAML::Node& node, absl::string_view path,
                                      std::optional<absl::Span<const absl::string_view>> allowed,
                                      ReadEntry read) {
  const std::string name = path.empty() ? "the document" : Shown(path);
  if (!node.IsMap()) {
    return Error(path, node,
                 !allowed.has_value()
                     ? absl::StrCat(name, " must be a mapping")
                     : absl::StrCat(name, " must be a mapping with keys ",
                                    absl::StrJoin(*allowed, ", ")));
  }
  std::set<std::string> seen;
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) {
      return Error(path, entry.first, "a key must be a name, not a list or mapping");
    }
    const std::string key = entry.first.Scalar();
    const std::string key_path = KeyPath(path, key);
    if (allowed.has_value()) {
      bool known = false;
      for (absl::string_view a : *allowed) known = known || a == key;
      if (!known) {
        return Error(key_path, entry.first,
                     absl::StrCat("unknown key '", key, "' ",
                                  path.empty() ? std::string("at the top level")
                                               : absl::StrCat("in ", Shown(path)),
                                  " (allowed: ", absl::StrJoin(*allowed, ", "), ")"));
      }
    }
    if (!seen.insert(key).second) {
      return Error(key_path, entry.first, absl::StrCat("key '", key, "' given twice"));
    }
    Note(key_path, entry.second);
    DCS_RETURN_IF_ERROR(read(key, entry.second, key_path));
  }
  return absl::OkStatus();
}

absl::Status YamlReader::ForEachItem(
    const YAML::Node& node, absl::string_view path, absl::string_view what,
    absl::FunctionRef<absl::Status(const YAML::Node& item, const std::string& item_path)> read) {
  if (!node.IsSequence()) return Error(path, node, absl::StrCat("must be ", what));
  for (size_t i = 0; i < node.size(); ++i) {
    const std::string item_path = ItemPath(path, i);
    Note(item_path, node[i]);
    DCS_RETURN_IF_ERROR(read(node[i], item_path));
  }
  return absl::OkStatus();
}

absl::Status YamlReader::PlainScalar(const YAML::Node& node, absl::string_view path,
                                     absl::string_view what) const {
  if (node.IsNull()) return Error(path, node, absl::StrCat("must be ", what, ", got null"));
  if (!node.IsScalar()) {
    return Error(
        path, node,
        absl::StrCat("must be ", what, ", got a ", node.IsSequence() ? "list" : "mapping"));
  }
  if (!IsPlain(node)) {
    return Error(path, node,
                 absl::StrCat("must be ", what, ", got the string \"", node.Scalar(), "\""));
  }
  return absl::OkStatus();
}

absl::StatusOr<double> YamlReader::Number(const YAML::Node& node, absl::string_view path) const {
  DCS_RETURN_IF_ERROR(PlainScalar(node, path, "a number"));
  const std::string& text = node.Scalar();
  const std::optional<double> value = ParseNumber(text);
  if (!value.has_value()) {
    return Error(path, node, absl::StrCat("must be a number, got '", text, "'"));
  }
  if (!std::isfinite(*value)) {
    return Error(path, node, absl::StrCat("must be a finite number, got '", text, "'"));
  }
  return *value;
}

template <typename T>
absl::StatusOr<T> YamlReader::Integer(const YAML::Node& node, absl::string_view path) const {
  const std::string what = std::is_signed_v<T> ? "an integer" : "a non-negative integer";
  DCS_RETURN_IF_ERROR(PlainScalar(node, path, what));
  const std::string& text = node.Scalar();
  absl::string_view digits = text;
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  T value{};
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc() && end == digits.data() + digits.size()) return value;
  const std::string range = absl::StrCat(" in [", std::numeric_limits<T>::min(), ", ",
                                         std::numeric_limits<T>::max(), "]");
  if (error == std::errc::result_out_of_range) {
    return Error(path, node, absl::StrCat("must be ", what, range, ", got ", text));
  }
  const std::optional<double> number = ParseNumber(text);
  if (!number.has_value() || !std::isfinite(*number) || *number != std::trunc(*number)) {
    return Error(path, node, absl::StrCat("must be ", what, ", got '", text, "'"));
  }
  if (std::abs(*number) > kMaxExactInteger ||
      *number < static_cast<double>(std::numeric_limits<T>::min()) ||
      *number > static_cast<double>(std::numeric_limits<T>::max())) {
    return Error(path, node, absl::StrCat("must be ", what, range, ", got ", text));
  }
  return static_cast<T>(*number);
}

absl::StatusOr<int> YamlReader::Int(const YAML::Node& node, absl::string_view path) const {
  return Integer<int>(node, path);
}

absl::StatusOr<int64_t> YamlReader::Int64(const YAML::Node& node, absl::string_view path) const {
  return Integer<int64_t>(node, path);
}

absl::StatusOr<uint64_t> YamlReader::Uint64(const YAML::Node& node,
                                            absl::string_view path) const {
  return Integer<uint64_t>(node, path);
}

absl::StatusOr<bool> YamlReader::Bool(const YAML::Node& node, absl::string_view path) const {
  DCS_RETURN_IF_ERROR(PlainScalar(node, path, "true or false"));
  bool value = false;
  if (!YAML::convert<bool>::decode(node, value)) {
    return Error(path, node, absl::StrCat("must be true or false, got '", node.Scalar(), "'"));
  }
  return value;
}

absl::StatusOr<std::string> YamlReader::Word(const YAML::Node& node,
                                             absl::string_view path) const {
  if (node.IsNull()) return Error(path, node, "must be a name, got null");
  if (!node.IsScalar()) return Error(path, node, "must be a name, not a list or mapping");
  return node.Scalar();
}

absl::StatusOr<std::variant<double, std::string>> YamlReader::NumberOrWord(
    const YAML::Node& node, absl::string_view path) const {
  DCS_ASSIGN_OR_RETURN(std::string word, Word(node, path));
  if (IsPlain(node) && ParseNumber(word).has_value()) {
    DCS_ASSIGN_OR_RETURN(const double number, Number(node, path));
    return number;
  }
  return word;
}

absl::StatusOr<std::vector<double>> YamlReader::Numbers(const YAML::Node& node,
                                                        absl::string_view path) {
  std::vector<double> values;
  DCS_RETURN_IF_ERROR(ForEachItem(node, path, "a list of numbers",
                                  [&](const YAML::Node& item, const std::string& item_path) {
                                    DCS_ASSIGN_OR_RETURN(const double value,
                                                         Number(item, item_path));
                                    values.push_back(value);
                                    return absl::OkStatus();
                                  }));
  return values;
}

absl::StatusOr<std::vector<int>> YamlReader::Ints(const YAML::Node& node,
                                                  absl::string_view path) {
  std::vector<int> values;
  DCS_RETURN_IF_ERROR(ForEachItem(node, path, "a list of integers",
                                  [&](const YAML::Node& item, const std::string& item_path) {
                                    DCS_ASSIGN_OR_RETURN(const int value, Int(item, item_path));
                                    values.push_back(value);
                                    return absl::OkStatus();
                                  }));
  return values;
}

}  // namespace dcs::run
