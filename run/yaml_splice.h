// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_YAML_SPLICE_H_
#define DCS_RUN_YAML_SPLICE_H_

// YAML documents spliced from the nodes of others, as a sweep spec makes each trial's run config
// from its base, a condition and grid values (run/sweep_spec_yaml.h). The nodes taken keep their
// marks, so a reader of the new document (run/yaml_reader.h) reports the lines where they were
// written, and the documents taken from are never changed.
//
// yaml-cpp's assignment to a node (`a = b`, `map[key] = b`) changes the node `a` refers to,
// which the other documents share: spliced documents are built by inserting (force_insert,
// push_back) into new nodes, and nodes are held by construction (std::optional::emplace), never
// assigned. Functions are thread-safe (the nodes given are only read); a YamlArena is
// thread-compatible.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"

namespace dcs::run {

// New nodes for documents spliced from another document's nodes. yaml-cpp keeps the nodes of a
// document in one pool, and putting a node into a node of another pool merges the two by
// copying one's whole node set into the other: splicing many documents from one spec's nodes
// would copy the spec's pool again for every new node. An arena's nodes share one pool with
// `document`, merged once. The pool keeps every node it holds until the arena, `document` and
// every node spliced from them are gone.
class YamlArena {
 public:
  explicit YamlArena(const YAML::Node& document);

  // A new, empty mapping or list (`type`) in the arena's pool.
  YAML::Node New(YAML::NodeType::value type);

 private:
  YAML::Node nodes_;  // a list of `document` and every node made, which holds the pool
};

// One step of a key path: into a mapping by key, or into a list by index.
struct KeyPathStep {
  std::string key;              // when `index` is empty
  std::optional<size_t> index;  // a list's item

  friend bool operator==(const KeyPathStep&, const KeyPathStep&) = default;
};

// The steps of `path`, or nullopt if it is no key path: names (letters, digits, '_', '-')
// joined by '.', each followed by any number of indices "[i]" ("stages[1].schedule.period" is
// stages, [1], schedule, period).
std::optional<std::vector<KeyPathStep>> ParseKeyPath(absl::string_view path);

// The text of `steps`, as ParseKeyPath reads it.
std::string KeyPathText(absl::Span<const KeyPathStep> steps);

// Whether one path is the other or leads into it (`schedule` and `schedule.period`): values
// placed at both would overwrite one another.
bool KeyPathsOverlap(absl::Span<const KeyPathStep> a, absl::Span<const KeyPathStep> b);

// `root` with `value` at `steps`, made in `arena` (which holds `root` and `value`). Each
// mapping and list on the path is copied with the entry the path takes replaced, and a mapping
// that is absent or null is created (its path added to `created`, if given); the rest is
// shared. INVALID_ARGUMENT saying which step cannot be taken: a key into something other than a
// mapping, an index into something other than a list or past its end.
absl::StatusOr<YAML::Node> WithValueAt(YamlArena& arena, const YAML::Node& root,
                                       absl::Span<const KeyPathStep> steps,
                                       const YAML::Node& value,
                                       std::vector<std::string>* created = nullptr);

// The value of `key` in the mapping `node` (the first, if the key is repeated), or nullopt.
std::optional<YAML::Node> FindKey(const YAML::Node& node, absl::string_view key);

// The mapping `base` with `over`'s entries in place of its own, made in `arena`: the entries of
// `base` whose keys `over` lacks, then all of `over`'s (a repeated key stays repeated, for a
// strict reader to refuse).
YAML::Node MergedMapping(YamlArena& arena, const YAML::Node& base, const YAML::Node& over);

// `node` in one line, for names: a scalar's text as written (without quotes), lists and
// mappings in flow style ("[1, 2]", "{size: 3}"), "null" for null.
std::string FlowText(const YAML::Node& node);

// `document` as YAML text that reads back to the same values: each collection in its style,
// numbers and other plain scalars as written (3.0e-4 stays 3.0e-4), quoted scalars quoted (so
// "125" stays a string), shared nodes written out each time (no anchors).
std::string YamlText(const YAML::Node& document);

}  // namespace dcs::run

#endif  // DCS_RUN_YAML_SPLICE_H_
