// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_STATUS_UTIL_H_
#define DCS_COMMON_STATUS_UTIL_H_

// Small helpers for absl::Status that every folder uses. Thread-safe (pure functions).

#include "absl/strings/string_view.h"

#include "absl/status/status.h"

namespace dcs {

// Returns `status` with "context: " prepended to its message, keeping its code; OK stays OK.
// Used on the way up, so the message read by a person names where the error came from.
absl::Status Annotate(const absl::Status& status, absl::string_view context);

}  // namespace dcs

#endif  // DCS_COMMON_STATUS_UTIL_H_
