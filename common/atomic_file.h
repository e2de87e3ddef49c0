// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_ATOMIC_FILE_H_
#define DCS_COMMON_ATOMIC_FILE_H_

// Whole-file writes that readers never see half done and that survive a crash: write a
// temporary file in the same directory, fsync it, rename it over the target, fsync the
// directory. Thread-safe for distinct paths.

#include <sys/types.h>

#include <string>

#include "absl/strings/string_view.h"

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace dcs {

// Replaces `path` with `contents`, created with permissions `mode` (less the umask; 0600 for
// a secret). On failure (a full disk, a missing directory) the old file is untouched and the
// error names the path and the reason: RESOURCE_EXHAUSTED for a full disk or quota, NOT_FOUND
// for a missing directory, PERMISSION_DENIED, else INTERNAL.
absl::Status WriteFileAtomically(const std::string& path, absl::string_view contents,
                                 mode_t mode = 0644);

// Moves the finished, fsync'd file `temporary` onto `path` (in the same directory) and fsyncs
// the directory, for a file written otherwise than by WriteFileAtomically (a database SQLite
// wrote). On failure `temporary` is removed. Errors as WriteFileAtomically's.
absl::Status RenameDurably(const std::string& temporary, const std::string& path);

// The error of a failed system call on `path` (`error` is its errno), as WriteFileAtomically
// reports it: "<what> <path>: <reason>", coded as it says.
absl::Status FileError(int error, absl::string_view what, const std::string& path);

// The whole contents of `path`. NOT_FOUND if it does not exist.
absl::StatusOr<std::string> ReadFile(const std::string& path);

}  // namespace dcs

#endif  // DCS_COMMON_ATOMIC_FILE_H_
