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

// Each use declares its hidden variable under a name of its own (__COUNTER__), so uses nest:
// a lambda inside one macro's argument may use the macros again without shadowing.
#define DCS_RETURN_IF_ERROR(expr) \
  DCS_RETURN_IF_ERROR_IMPL_(DCS_STATUS_CONCAT_(dcs_status_, __COUNTER__), expr)

#define DCS_RETURN_IF_ERROR_IMPL_(status, expr)               \
  do {                                                        \
    if (::absl::Status status = (expr); !status.ok()) {       \
      return status;                                          \
    }                                                         \
  } while (false)

#define DCS_ASSIGN_OR_RETURN(lhs, rexpr) \
  DCS_ASSIGN_OR_RETURN_IMPL_(DCS_STATUS_CONCAT_(dcs_statusor_, __COUNTER__), lhs, rexpr)

#define DCS_ASSIGN_OR_RETURN_IMPL_(statusor, lhs, rexpr) \
  auto statusor = (rexpr);                                \
  if (!statusor.ok()) {                                   \
    return std::move(statusor).status();                  \
  }                                                       \
  lhs = *std::move(statusor)

#define DCS_STATUS_CONCAT_(a, b) DCS_STATUS_CONCAT_IMPL_(a, b)
#define DCS_STATUS_CONCAT_IMPL_(a, b) a##b

#endif  // DCS_COMMON_STATUS_MACROS_H_
