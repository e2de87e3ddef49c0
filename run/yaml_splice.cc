// Copyright 2026 The DCS Authors.
#include "run/yaml_splice.h"

#include <algorithm>
#include <charconv>
#include <utility>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "run/config_errors.h"

namespace dcs::run {
namespace {

bool IsNameChar(char c) { return absl::ascii_isalnum(c) || c == '_' || c == '-'; }

absl::StatusOr<YAML::Node> Place(YamlArena& arena, const YAML::Node& node,
                                 absl::Span<const KeyPathStep> steps, size_t at,
                                 const YAML::Node& value, std::vector<std::string>* created) {
  if (at == steps.size()) return value;
  const KeyPathStep& step = steps[at];
  const std::string here = KeyPathText(steps.first(at));
  if (step.index.has_value()) {
    if (!node.IsSequence()) {
      return absl::InvalidArgumentError(
          absl::StrCat("there is no list ", here, " to take item ", *step.index, " of"));
    }
    if (*step.index >= node.size()) {
      return absl::InvalidArgumentError(absl::StrCat(here, " has ", node.size(),
                                                     " items, so no item ", *step.index));
    }
    YAML::Node copy = arena.New(YAML::NodeType::Sequence);
    copy.SetStyle(node.Style());
    for (size_t i = 0; i < node.size(); ++i) {
      if (i != *step.index) {
        copy.push_back(node[i]);
        continue;
      }
      absl::StatusOr<YAML::Node> item = Place(arena, node[i], steps, at + 1, value, created);
      if (!item.ok()) return item.status();
      copy.push_back(*item);
    }
    return copy;
  }
  if (node.IsDefined() && !node.IsNull() && !node.IsMap()) {
    return absl::InvalidArgumentError(absl::StrCat(
        here, " is a ", node.IsSequence() ? "list" : "single value", ", not a mapping with '",
        step.key, "'"));
  }
  // The entry's value (the first, if the key is repeated: the run config's reader refuses the
  // repetition, which the copy keeps).
  std::optional<YAML::Node> inner;
  if (node.IsMap()) {
    for (const auto& entry : node) {
      if (!inner.has_value() && entry.first.IsScalar() && entry.first.Scalar() == step.key) {
        inner.emplace(entry.second);
      }
    }
  }
  absl::StatusOr<YAML::Node> placed =
      Place(arena, inner.value_or(YAML::Node()), steps, at + 1, value, created);
  if (!placed.ok()) return placed.status();
  if (!node.IsMap() && created != nullptr) created->push_back(here);
  YAML::Node copy = arena.New(YAML::NodeType::Map);
  if (node.IsMap()) copy.SetStyle(node.Style());
  bool replaced = false;
  if (node.IsMap()) {
    for (const auto& entry : node) {
      const bool taken = !replaced && entry.first.IsScalar() && entry.first.Scalar() == step.key;
      copy.force_insert(entry.first, taken ? *placed : entry.second);
      replaced = replaced || taken;
    }
  }
  if (!replaced) copy.force_insert(step.key, *placed);
  return copy;
}

// A scalar a strict reader takes as written (run/yaml_reader.h): no quotes, no tag but a
// core-schema one.
bool IsPlain(const YAML::Node& node) {
  const std::string& tag = node.Tag();
  return tag == "?" || tag == "tag:yaml.org,2002:int" || tag == "tag:yaml.org,2002:float" ||
         tag == "tag:yaml.org,2002:bool";
}

void Emit(YAML::Emitter& out, const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      if (!IsPlain(node)) out << YAML::DoubleQuoted;
      out << node.Scalar();
      return;
    case YAML::NodeType::Sequence:
      if (node.Style() == YAML::EmitterStyle::Flow) out << YAML::Flow;
      out << YAML::BeginSeq;
      for (const auto& item : node) Emit(out, item);
      out << YAML::EndSeq;
      return;
    case YAML::NodeType::Map:
      if (node.Style() == YAML::EmitterStyle::Flow) out << YAML::Flow;
      out << YAML::BeginMap;
      for (const auto& entry : node) {
        out << YAML::Key;
        Emit(out, entry.first);
        out << YAML::Value;
        Emit(out, entry.second);
      }
      out << YAML::EndMap;
      return;
    default:
      out << YAML::Null;
  }
}

}  // namespace

YamlArena::YamlArena(const YAML::Node& document) : nodes_(YAML::NodeType::Sequence) {
  nodes_.push_back(document);
}

YAML::Node YamlArena::New(YAML::NodeType::value type) {
  YAML::Node node(type);
  nodes_.push_back(node);  // before anything goes in: its pool becomes the arena's
  return node;
}

std::optional<std::vector<KeyPathStep>> ParseKeyPath(absl::string_view path) {
  std::vector<KeyPathStep> steps;
  size_t i = 0;
  while (true) {
    const size_t start = i;
    while (i < path.size() && IsNameChar(path[i])) ++i;
    if (i == start) return std::nullopt;
    steps.push_back({.key = std::string(path.substr(start, i - start))});
    while (i < path.size() && path[i] == '[') {
      const size_t digits = ++i;
      while (i < path.size() && absl::ascii_isdigit(path[i])) ++i;
      size_t index = 0;
      auto [end, error] = std::from_chars(path.data() + digits, path.data() + i, index);
      if (i == digits || error != std::errc() || i == path.size() || path[i] != ']') {
        return std::nullopt;
      }
      steps.push_back({.index = index});
      ++i;
    }
    if (i == path.size()) return steps;
    if (path[i] != '.') return std::nullopt;
    ++i;
  }
}

bool KeyPathsOverlap(absl::Span<const KeyPathStep> a, absl::Span<const KeyPathStep> b) {
  const size_t common = std::min(a.size(), b.size());
  return std::equal(a.begin(), a.begin() + common, b.begin());
}

absl::StatusOr<YAML::Node> WithValueAt(YamlArena& arena, const YAML::Node& root,
                                       absl::Span<const KeyPathStep> steps,
                                       const YAML::Node& value,
                                       std::vector<std::string>* created) {
  return Place(arena, root, steps, 0, value, created);
}

std::string KeyPathText(absl::Span<const KeyPathStep> steps) {
  std::string path;
  for (const KeyPathStep& step : steps) {
    path = step.index.has_value() ? ItemPath(path, *step.index) : KeyPath(path, step.key);
  }
  return path;
}

std::optional<YAML::Node> FindKey(const YAML::Node& node, absl::string_view key) {
  if (!node.IsMap()) return std::nullopt;
  for (const auto& entry : node) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) return YAML::Node(entry.second);
  }
  return std::nullopt;
}

YAML::Node MergedMapping(YamlArena& arena, const YAML::Node& base, const YAML::Node& over) {
  YAML::Node merged = arena.New(YAML::NodeType::Map);
  for (const auto& entry : base) {
    if (!entry.first.IsScalar() || !FindKey(over, entry.first.Scalar()).has_value()) {
      merged.force_insert(entry.first, entry.second);
    }
  }
  for (const auto& entry : over) merged.force_insert(entry.first, entry.second);
  return merged;
}

std::string FlowText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  std::vector<std::string> parts;
  if (node.IsSequence()) {
    for (const auto& item : node) parts.push_back(FlowText(item));
    return absl::StrCat("[", absl::StrJoin(parts, ", "), "]");
  }
  if (node.IsMap()) {
    for (const auto& entry : node) {
      parts.push_back(absl::StrCat(FlowText(entry.first), ": ", FlowText(entry.second)));
    }
    return absl::StrCat("{", absl::StrJoin(parts, ", "), "}");
  }
  return "null";
}

std::string YamlText(const YAML::Node& document) {
  YAML::Emitter out;
  Emit(out, document);
  return absl::StrCat(out.c_str(), "\n");
}

}  // namespace dcs::run
