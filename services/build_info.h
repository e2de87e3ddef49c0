// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_BUILD_INFO_H_
#define DCS_SERVICES_BUILD_INFO_H_

// What a DCS process reports about its own build: `dcs version`, the dcs_build_info metric,
// and worker registration. Thread-safe (pure functions).

#include <string>
#include <vector>

#include "common/library_version.h"

namespace dcs::services {

// The build of one process: DCS itself and the third-party libraries it links.
struct BuildInfo {
  std::string version;  // DcsVersion()
  std::vector<LibraryVersion> libraries;
};

// This build of DCS: release and git commit, "0.1.0+3f2a9c1".
std::string DcsVersion();

// DcsVersion(), ServiceLibraryVersions() and then `own_libraries`.
BuildInfo ProcessBuildInfo(const std::vector<LibraryVersion>& own_libraries);

// The libraries every DCS process links for its service plumbing: gRPC, protobuf, abseil,
// prometheus-cpp and yaml-cpp. A process appends those of the DCS libraries it runs
// (dcs::env::LibraryVersions() and its siblings).
std::vector<LibraryVersion> ServiceLibraryVersions();

// libtorch as dcs-train and dcs-learner are compiled against (the version of the package CMake
// found), known without loading it: for the programs that do not link it. Those that do report
// it, and the kernels it runs, themselves (learner::LibraryVersions()).
LibraryVersion CompiledLibtorchVersion();

}  // namespace dcs::services

#endif  // DCS_SERVICES_BUILD_INFO_H_
