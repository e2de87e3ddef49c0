// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_STATUS_MACROS_H_
#define DCS_COMMON_STATUS_MACROS_H_

// DCS_RETURN_IF_ERROR and DCS_ASSIGN_OR_RETURN: early returns for absl::Status and
// absl::StatusOr<T>. Abseil 20220623 (Debian 12) has no macros of its own.
//
//   DCS_RETURN_IF_ERROR(store.Open(path));
//   DCS_ASSIGN_OR_RETURN(Config config, ParseConfig(text));

#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

#define DCS_RETURN_IF_ERROR(expr)                          \
  do {                                                     \
    if (::absl::Status dcs_status_ = (expr); !dcs_status_.ok()) { \
      return dcs_status_;                                  \
    }                                                      \
  } while (false)

#define DCS_ASSIGN_OR_RETURN(lhs, rexpr) \
  DCS_ASSIGN_OR_RETURN_IMPL_(DCS_STATUS_CONCAT_(dcs_statusor_, __LINE__), lhs, rexpr)

#define DCS_ASSIGN_OR_RETURN_IMPL_(statusor, lhs, rexpr) \
  auto statusor = (rexpr);                                \
  if (!statusor.ok()) {                                   \
    return std::move(statusor).status();                  \
  }                                                       \
  lhs = *std::move(statusor)

#define DCS_STATUS_CONCAT_(a, b) DCS_STATUS_CONCAT_IMPL_(a, b)
#define DCS_STATUS_CONCAT_IMPL_(a, b) a##b

#endif  // DCS_COMMON_STATUS_MACROS_H_
