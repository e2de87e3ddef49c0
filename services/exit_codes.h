// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_EXIT_CODES_H_
#define DCS_SERVICES_EXIT_CODES_H_

// The exit codes of every DCS program (documented in README.md's table), after <sysexits.h>
// where one fits. Thread-safe (constants and pure functions).

#include "absl/status/status.h"
#include "absl/strings/string_view.h"

namespace dcs::services {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;       // anything not listed below
inline constexpr int kExitUsage = 2;         // unknown flag or command, bad flag value (UsageError)
inline constexpr int kExitDataError = 65;    // INVALID_ARGUMENT: bad input data (EX_DATAERR)
inline constexpr int kExitNoInput = 66;      // NOT_FOUND: a named input does not exist (EX_NOINPUT)
inline constexpr int kExitUnavailable = 69;  // UNAVAILABLE, DEADLINE_EXCEEDED (EX_UNAVAILABLE)
inline constexpr int kExitNoPermission = 77; // UNAUTHENTICATED, PERMISSION_DENIED (EX_NOPERM)
inline constexpr int kExitConfig = 78;       // unreadable or malformed config file (EX_CONFIG)
inline constexpr int kExitInterrupted = 130; // stopped by SIGINT or SIGTERM, resumable (128 + 2)

// The exit code for a program that fails with `status`. REQUIRES: !status.ok().
int ExitCodeFor(const absl::Status& status);

// INVALID_ARGUMENT for a command line the program cannot run as given: a required input
// missing, flags that exclude each other, a flag's value not of its type. ExitCodeFor maps it
// to kExitUsage rather than kExitDataError (bad data in what the command reads).
absl::Status UsageError(absl::string_view message);

}  // namespace dcs::services

#endif  // DCS_SERVICES_EXIT_CODES_H_
