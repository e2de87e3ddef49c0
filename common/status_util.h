// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_STATUS_UTIL_H_
#define DCS_COMMON_STATUS_UTIL_H_

// Small helpers for absl::Status that every folder uses. Thread-safe (pure functions).

#include <optional>
#include <string>

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace dcs {

// Returns `status` with "context: " prepended to its message, keeping its code; OK stays OK.
// Used on the way up, so the message read by a person names where the error came from.
absl::Status Annotate(const absl::Status& status, absl::string_view context);

// The field an error is about, carried with it as a status payload. A validator names the field
// in its own terms ("period"); each caller that nests it adds its own part in front
// ("parts[1]" makes "parts[1].period"); the reader that knows where the config was written
// turns the whole into a path and a line (run/schedule_yaml.h: ScheduleError). The message is
// unchanged; OK stays OK.
absl::Status ErrorInField(absl::Status status, absl::string_view field);
// The field ErrorInField recorded, or nullopt.
std::optional<std::string> ErrorField(const absl::Status& status);

}  // namespace dcs

#endif  // DCS_COMMON_STATUS_UTIL_H_
