// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_LIBRARY_VERSIONS_H_
#define DCS_ENV_LIBRARY_VERSIONS_H_

// The physics and linear-algebra libraries the environments compute with. Thread-safe.

#include <vector>

#include "common/library_version.h"

namespace dcs::env {

// Box2D and Eigen.
std::vector<LibraryVersion> LibraryVersions();

}  // namespace dcs::env

#endif  // DCS_ENV_LIBRARY_VERSIONS_H_
