// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_ROUND_TRIP_H_
#define DCS_COMMON_ROUND_TRIP_H_

// Doubles as the shortest text that reads back as the same value (std::to_chars), for CSV and
// logs that results are compared against bit for bit. Thread-safe.

#include <charconv>
#include <string>

namespace dcs {

inline std::string RoundTrip(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace dcs

#endif  // DCS_COMMON_ROUND_TRIP_H_
