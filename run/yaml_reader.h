// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_YAML_READER_H_
#define DCS_RUN_YAML_READER_H_

// Strict reading of DCS's YAML files (run configs, schedules and sweep specs; search spaces
// next). Every value is read at its YAML path (`stages[1].schedule.period`), and every error
// says where, as
//
//   run.yaml: evaluation.freq: line 9: must be an integer, got 'often'
//
// One number rule everywhere: a number is a plain (unquoted) scalar that std::from_chars reads
// whole, after an optional '+'; it must be finite ("nan", "inf" are refused, ".inf" is not a
// number). A quoted scalar is a string, never a number. An integer is digits, or a number with
// an integral value ("3e6") up to 2^53 (beyond it a double names no single integer), and within
// its type. A mapping's keys are names, each given once.
//
// Errors found after reading (by validation) are formatted the same way, with the line of the
// field when the reader saw it (errors(), run/config_errors.h). Thread-compatible.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "absl/functional/function_ref.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "run/config_errors.h"

namespace dcs::run {

class YamlReader {
 public:
  // Reads values of the document named `where` in errors (a file path). With `shown_path`,
  // errors show each field's path through it (run/config_errors.h: a sweep spec's trial shows
  // its fields where the spec wrote them); lines are those of the nodes read either way.
  explicit YamlReader(std::string where, PathMap shown_path = nullptr)
      : where_(std::move(where)), shown_path_(std::move(shown_path)) {}

  // The name of the document in errors.
  const std::string& where() const { return where_; }

  // The document in `text`. INVALID_ARGUMENT "<where>: line L, column C: <problem>" for
  // malformed YAML.
  absl::StatusOr<YAML::Node> Load(absl::string_view text) const;

  // "<where>: <path>: line <n>: <message>" for `node` (no path at the top level, no line for a
  // node that has none).
  absl::Status Error(absl::string_view path, const YAML::Node& node,
                     absl::string_view message) const;

  // Calls `read(key, value, key_path)` for each entry of the mapping `node` at `path`, in
  // order, noting each value's line. With `allowed`, keys must be among them; without, any
  // name is a key. Errors: not a mapping; a key that is not a name, unknown (listing the
  // allowed ones) or repeated; the first error `read` returns.
  using ReadEntry = absl::FunctionRef<absl::Status(const std::string& key,
                                                   const YAML::Node& value,
                                                   const std::string& key_path)>;
  absl::Status ForEachKey(const YAML::Node& node, absl::string_view path,
                          absl::Span<const absl::string_view> allowed, ReadEntry read);
  absl::Status ForEachEntry(const YAML::Node& node, absl::string_view path, ReadEntry read);

  // Calls `read(item, item_path)` for each item of the list `node` at `path`, noting each
  // item's line. `what` describes the expected list in the error for anything else.
  absl::Status ForEachItem(
      const YAML::Node& node, absl::string_view path, absl::string_view what,
      absl::FunctionRef<absl::Status(const YAML::Node& item, const std::string& item_path)> read);

  // Scalars, by the number rule above. Each error names what was expected and what was found.
  absl::StatusOr<double> Number(const YAML::Node& node, absl::string_view path) const;
  absl::StatusOr<int> Int(const YAML::Node& node, absl::string_view path) const;
  absl::StatusOr<int64_t> Int64(const YAML::Node& node, absl::string_view path) const;
  absl::StatusOr<uint64_t> Uint64(const YAML::Node& node, absl::string_view path) const;
  absl::StatusOr<bool> Bool(const YAML::Node& node, absl::string_view path) const;
  // A scalar, quoted or not, as written.
  absl::StatusOr<std::string> Word(const YAML::Node& node, absl::string_view path) const;
  // A number if the number rule makes the scalar one, else its text (a word); a plain scalar
  // that reads as a non-finite number is an error.
  absl::StatusOr<std::variant<double, std::string>> NumberOrWord(const YAML::Node& node,
                                                                 absl::string_view path) const;

  // Lists of numbers; each item's line is noted as `path[i]`.
  absl::StatusOr<std::vector<double>> Numbers(const YAML::Node& node, absl::string_view path);
  absl::StatusOr<std::vector<int>> Ints(const YAML::Node& node, absl::string_view path);

  // Errors at the fields read so far, for validation after reading. Borrows the reader's
  // lines: the reader must outlive it.
  ConfigErrors errors() const { return ConfigErrors(where_, &lines_, &shown_path_); }

 private:
  // Records that the field at `path` is `node`'s (for errors found later).
  void Note(const std::string& path, const YAML::Node& node);
  // The path errors show for `path`.
  std::string Shown(absl::string_view path) const;
  template <typename T>
  absl::StatusOr<T> Integer(const YAML::Node& node, absl::string_view path) const;
  absl::Status PlainScalar(const YAML::Node& node, absl::string_view path,
                           absl::string_view what) const;
  absl::Status ForEachKeyOf(const YAML::Node& node, absl::string_view path,
                            std::optional<absl::Span<const absl::string_view>> allowed,
                            ReadEntry read);

  std::string where_;
  PathMap shown_path_;
  std::map<std::string, int> lines_;
};

}  // namespace dcs::run

#endif  // DCS_RUN_YAML_READER_H_
