// Copyright 2026 The DCS Authors.
#include "coordinator/library_versions.h"

#include <sqlite3.h>

namespace dcs::coordinator {

std::vector<LibraryVersion> LibraryVersions() { return {{"sqlite", sqlite3_libversion()}}; }

}  // namespace dcs::coordinator
