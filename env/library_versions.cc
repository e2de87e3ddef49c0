// Copyright 2026 The DCS Authors.
#include "env/library_versions.h"

#include <Eigen/Core>

#include "absl/strings/str_cat.h"

namespace dcs::env {

std::vector<LibraryVersion> LibraryVersions() {
  return {
      // Box2D 2.4.1 still sets its runtime b2_version to 2.4.0, so CMake passes the version of
      // the package it found.
      {"box2d", DCS_BOX2D_VERSION},
      {"eigen", absl::StrCat(EIGEN_WORLD_VERSION, ".", EIGEN_MAJOR_VERSION, ".",
                             EIGEN_MINOR_VERSION)},
  };
}

}  // namespace dcs::env
