// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_CONFIG_KEYS_H_
#define DCS_RUN_CONFIG_KEYS_H_

// The keys of one mapping of a YAML config as one table, the only list of them. A row names a
// key, the field of the config's struct it is read into, the bound its check holds it to, and
// what it means. The reader takes the keys a mapping allows from the table (names(), for
// YamlReader::ForEachKey) and reads each field through its row (ReadField); validation checks
// each bound through it (CheckBounds); docs/config.md shows the rows (Describe), each default
// read from the struct's default instance. A key the reader reads with code of its own (a
// schedule, a mapping with keys of its own) has no field: its row says how the value is written
// and what it defaults to.
//
//   const KeyTable<RunSpec> kEvaluation({
//       {.name = "freq", .meaning = "environment steps between evaluations",
//        .field = &RunSpec::eval_freq, .bound = AtLeast(1)},
//       {.name = "contexts", .meaning = "...", .type = "mapping", .default_value = "required"}});
//
// A table is built once and never changes: thread-safe.

#include <yaml-cpp/yaml.h>

#include <cassert>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"
#include "absl/types/span.h"
#include "common/config_doc.h"
#include "run/config_errors.h"
#include "run/yaml_reader.h"

namespace dcs::run {

// The numbers a field may hold: finite, in [lo, hi], lo itself excluded if `lo_open`.
struct Bound {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;

  // False for a bound that allows every number (the default): nothing to check.
  bool bounded() const;
  bool Contains(double value) const;
  // The rule as errors state it after "must be ": "positive", "at least 1", "in [0, 1]".
  std::string Rule() const;
};
constexpr Bound AtLeast(double lo) { return Bound{.lo = lo}; }
constexpr Bound Positive() { return Bound{.lo = 0, .lo_open = true}; }
constexpr Bound Within(double lo, double hi) { return Bound{.lo = lo, .hi = hi}; }

template <typename S>
struct ConfigKey {
  using Field = std::variant<std::monostate, int S::*, int64_t S::*, uint64_t S::*, double S::*,
                             bool S::*, std::optional<double> S::*, std::string S::*,
                             std::vector<int> S::*, std::vector<double> S::*>;

  absl::string_view name;  // a literal, or another table's name: it outlives the table
  std::string meaning;     // one line, for the reference
  Field field;             // none: the reader reads the key with code of its own
  Bound bound;             // of a list, each item's
  // How the value is written and its default, where the field does not say it (a key without a
  // field; a name from a fixed list): shown as given. Empty: the field's.
  std::string type;
  std::string default_value;
  // What a list's items are, in the error for one out of bounds ("a list of positive widths").
  absl::string_view items = "values";

  bool has_field() const { return !std::holds_alternative<std::monostate>(field); }
};

template <typename S>
class KeyTable {
 public:
  explicit KeyTable(std::vector<ConfigKey<S>> keys) : keys_(std::move(keys)) {
    for (const ConfigKey<S>& key : keys_) names_.push_back(key.name);
  }

  const std::vector<ConfigKey<S>>& keys() const { return keys_; }
  // The keys' names in the table's order: the keys the mapping allows.
  absl::Span<const absl::string_view> names() const { return names_; }
  // The row of `name`, or null.
  const ConfigKey<S>* Find(absl::string_view name) const {
    for (const ConfigKey<S>& key : keys_) {
      if (key.name == name) return &key;
    }
    return nullptr;
  }
  // The row of `name`. REQUIRES: the table has it.
  const ConfigKey<S>& operator[](absl::string_view name) const {
    const ConfigKey<S>* key = Find(name);
    assert(key != nullptr);
    return *key;
  }

 private:
  std::vector<ConfigKey<S>> keys_;
  std::vector<absl::string_view> names_;
};

// Reads `node`, the value at `path`, into `key`'s field of `config`, as run/yaml_reader.h reads
// the field's type; an optional number takes null for none. Errors: the reader's. REQUIRES:
// `key` has a field.
template <typename S>
absl::Status ReadField(YamlReader& reader, const ConfigKey<S>& key, const YAML::Node& node,
                       const std::string& path, S& config);

// Adds to `problems`, in the table's order, a problem for each field of `config` outside its
// key's bound, at the key's path under `path`: "must be <rule>, got <value>", or for a list its
// first item outside, "must be a list of <rule> <items>, got <item>". Returns the names of the
// keys it found outside, for checks between fields that name a field once. A bound of a key
// without a field is the reader's own code's to check.
template <typename S>
std::set<absl::string_view> CheckBounds(const KeyTable<S>& table, const S& config,
                                        absl::string_view path, const ConfigErrors& errors,
                                        ConfigProblems& problems);

// The table's rows for the reference, in its order; each field's type from its C++ type, its
// default from `S{}`, its range from its bound.
template <typename S>
std::vector<KeyDoc> Describe(const KeyTable<S>& table);

// A value of a field's type as YAML writes it: "0.99", "true", "null", "[64, 64]".
template <typename T>
std::string ValueText(const T& value);

// Implementation details.

namespace internal {

template <typename T>
struct IsVector : std::false_type {};
template <typename T>
struct IsVector<std::vector<T>> : std::true_type {};

}  // namespace internal

template <typename T>
std::string ValueText(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return value.has_value() ? absl::StrCat(*value) : "null";
  } else if constexpr (internal::IsVector<T>::value) {
    std::string text = "[";
    for (size_t i = 0; i < value.size(); ++i) absl::StrAppend(&text, i == 0 ? "" : ", ", value[i]);
    return text + "]";
  } else {
    return absl::StrCat(value);
  }
}

namespace internal {

template <typename T>
absl::StatusOr<T> ReadValue(YamlReader& reader, const YAML::Node& node,
                            const std::string& path) {
  if constexpr (std::is_same_v<T, int>) {
    return reader.Int(node, path);
  } else if constexpr (std::is_same_v<T, int64_t>) {
    return reader.Int64(node, path);
  } else if constexpr (std::is_same_v<T, uint64_t>) {
    return reader.Uint64(node, path);
  } else if constexpr (std::is_same_v<T, double>) {
    return reader.Number(node, path);
  } else if constexpr (std::is_same_v<T, bool>) {
    return reader.Bool(node, path);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return reader.Word(node, path);
  } else if constexpr (std::is_same_v<T, std::vector<int>>) {
    return reader.Ints(node, path);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return reader.Numbers(node, path);
  } else {
    static_assert(std::is_same_v<T, std::optional<double>>);
    if (node.IsNull()) return T();
    absl::StatusOr<double> value = reader.Number(node, path);
    if (!value.ok()) return value.status();
    return T(*value);
  }
}

// How a user writes a value of type T.
template <typename T>
std::string TypeName() {
  if constexpr (std::is_same_v<T, int> || std::is_same_v<T, int64_t>) {
    return "integer";
  } else if constexpr (std::is_same_v<T, uint64_t>) {
    return "non-negative integer";
  } else if constexpr (std::is_same_v<T, double>) {
    return "number";
  } else if constexpr (std::is_same_v<T, bool>) {
    return "bool";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "string";
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return "number or null";
  } else {
    return absl::StrCat("list of ", TypeName<typename T::value_type>(), "s");
  }
}

// The problem of `value` with `bound` ("must be positive, got 0"; a list's first item outside
// it, "must be a list of positive <items>, got 0"), or nullopt. A word or a boolean has none.
template <typename T>
std::optional<std::string> BoundProblem(const Bound& bound, absl::string_view items,
                                        const T& value) {
  if constexpr (std::is_same_v<T, std::optional<double>>) {
    if (!value.has_value()) return std::nullopt;
    return BoundProblem(bound, items, *value);
  } else if constexpr (IsVector<T>::value) {
    for (const auto& item : value) {
      if (!bound.Contains(static_cast<double>(item))) {
        return absl::StrCat("must be a list of ", bound.Rule(), " ", items, ", got ",
                            ValueText(item));
      }
    }
    return std::nullopt;
  } else if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    if (bound.Contains(static_cast<double>(value))) return std::nullopt;
    return absl::StrCat("must be ", bound.Rule(), ", got ", ValueText(value));
  } else {
    return std::nullopt;
  }
}

}  // namespace internal

template <typename S>
absl::Status ReadField(YamlReader& reader, const ConfigKey<S>& key, const YAML::Node& node,
                       const std::string& path, S& config) {
  return std::visit(
      [&](auto field) -> absl::Status {
        if constexpr (std::is_same_v<decltype(field), std::monostate>) {
          assert(false && "ReadField of a key without a field");
          return absl::InternalError(absl::StrCat(path, ": no field to read into"));
        } else {
          using T = std::remove_cvref_t<decltype(config.*field)>;
          absl::StatusOr<T> value = internal::ReadValue<T>(reader, node, path);
          if (!value.ok()) return value.status();
          config.*field = *std::move(value);
          return absl::OkStatus();
        }
      },
      key.field);
}

template <typename S>
std::set<absl::string_view> CheckBounds(const KeyTable<S>& table, const S& config,
                                        absl::string_view path, const ConfigErrors& errors,
                                        ConfigProblems& problems) {
  std::set<absl::string_view> outside;
  for (const ConfigKey<S>& key : table.keys()) {
    if (!key.bound.bounded()) continue;
    std::visit(
        [&](auto field) {
          if constexpr (!std::is_same_v<decltype(field), std::monostate>) {
            std::optional<std::string> problem =
                internal::BoundProblem(key.bound, key.items, config.*field);
            if (!problem.has_value()) return;
            problems.Add(errors.At(KeyPath(path, key.name), *problem));
            outside.insert(key.name);
          }
        },
        key.field);
  }
  return outside;
}

template <typename S>
std::vector<KeyDoc> Describe(const KeyTable<S>& table) {
  // On the heap: GCC 12 takes a local's fields read through member pointers for uninitialised.
  const auto defaults = std::make_unique<const S>();
  std::vector<KeyDoc> docs;
  for (const ConfigKey<S>& key : table.keys()) {
    KeyDoc& doc = docs.emplace_back(KeyDoc{.name = std::string(key.name),
                                           .type = key.type,
                                           .default_value = key.default_value,
                                           .meaning = key.meaning});
    bool list = false;
    std::visit(
        [&](auto field) {
          if constexpr (!std::is_same_v<decltype(field), std::monostate>) {
            using T = std::remove_cvref_t<decltype((*defaults).*field)>;
            list = internal::IsVector<T>::value;
            if (doc.type.empty()) doc.type = internal::TypeName<T>();
            if (doc.default_value.empty()) {
              doc.default_value = ValueText((*defaults).*field);
            }
          }
        },
        key.field);
    if (key.bound.bounded()) doc.range = absl::StrCat(list ? "each " : "", key.bound.Rule());
  }
  return docs;
}

}  // namespace dcs::run

#endif  // DCS_RUN_CONFIG_KEYS_H_
