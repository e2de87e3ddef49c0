// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_ENUM_NAMES_H_
#define DCS_COMMON_ENUM_NAMES_H_

// One table per enumeration: each value with the name configs, logs and files spell it, in the
// enumeration's order. Everything that turns a value into a name or back reads the table, so
// a name is written once:
//
//   inline constexpr EnumName<Split> kSplitNames[] = {
//       {Split::kId, "id"}, {Split::kOodLow, "ood_low"}, {Split::kOodHigh, "ood_high"}};
//   static_assert(InEnumOrder(kSplitNames));
//
// Thread-safe (constant data, pure functions).

#include <array>
#include <cstddef>
#include <optional>
#include <string>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace dcs {

template <typename E>
struct EnumName {
  E value;
  absl::string_view name;
};

// True if entry i holds the value i, for every entry: the table lists every value of an
// enumeration numbered from 0, once, in order.
template <typename E, size_t N>
constexpr bool InEnumOrder(const EnumName<E> (&table)[N]) {
  for (size_t i = 0; i < N; ++i) {
    if (static_cast<size_t>(table[i].value) != i) return false;
  }
  return true;
}

// The name of `value`. REQUIRES: `value` is in the table.
template <typename E, size_t N>
constexpr absl::string_view NameOf(const EnumName<E> (&table)[N], E value) {
  for (const EnumName<E>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return {};
}

// The value called `name`, or nullopt.
template <typename E, size_t N>
constexpr std::optional<E> FindByName(const EnumName<E> (&table)[N], absl::string_view name) {
  for (const EnumName<E>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

// Every name, in order (the keys a config may use, say).
template <typename E, size_t N>
constexpr std::array<absl::string_view, N> NamesOf(const EnumName<E> (&table)[N]) {
  std::array<absl::string_view, N> names;
  for (size_t i = 0; i < N; ++i) names[i] = table[i].name;
  return names;
}

// The names for a message: "none, initial or live".
template <typename E, size_t N>
std::string ListNames(const EnumName<E> (&table)[N]) {
  std::string list;
  for (size_t i = 0; i < N; ++i) {
    absl::StrAppend(&list, i == 0 ? "" : (i + 1 == N ? " or " : ", "), table[i].name);
  }
  return list;
}

}  // namespace dcs

#endif  // DCS_COMMON_ENUM_NAMES_H_
