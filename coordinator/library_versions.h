// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_LIBRARY_VERSIONS_H_
#define DCS_COORDINATOR_LIBRARY_VERSIONS_H_

// The storage library the coordinator keeps its records with. Thread-safe.

#include <vector>

#include "common/library_version.h"

namespace dcs::coordinator {

// SQLite, read from the loaded library.
std::vector<LibraryVersion> LibraryVersions();

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_LIBRARY_VERSIONS_H_
