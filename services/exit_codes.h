// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_EXIT_CODES_H_
#define DCS_SERVICES_EXIT_CODES_H_

// The exit codes of every DCS program (documented in README.md), after <sysexits.h> where one
// fits. Thread-safe (constants and a pure function).

#include "absl/status/status.h"

namespace dcs::services {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;       // anything not listed below
inline constexpr int kExitUsage = 2;         // unknown flag, bad flag value
inline constexpr int kExitDataError = 65;    // INVALID_ARGUMENT: bad input data (EX_DATAERR)
inline constexpr int kExitUnavailable = 69;  // UNAVAILABLE, DEADLINE_EXCEEDED (EX_UNAVAILABLE)
inline constexpr int kExitNoPermission = 77; // UNAUTHENTICATED, PERMISSION_DENIED (EX_NOPERM)
inline constexpr int kExitConfig = 78;       // unreadable or malformed config file (EX_CONFIG)
inline constexpr int kExitInterrupted = 130; // stopped by SIGINT or SIGTERM, resumable (128 + 2)

// The exit code for a program that fails with `status`. REQUIRES: !status.ok().
int ExitCodeFor(const absl::Status& status);

}  // namespace dcs::services

#endif  // DCS_SERVICES_EXIT_CODES_H_
