// Copyright 2026 The DCS Authors.
#include "services/build_info.h"

#include <google/protobuf/stubs/common.h>
#include <grpcpp/grpcpp.h>
#include <httplib.h>

#include "absl/base/config.h"
#include "absl/strings/str_cat.h"
#include "services/build_version.h"

namespace dcs::services {

std::string DcsVersion() { return absl::StrCat(DCS_VERSION, "+", DCS_GIT_SHA); }

BuildInfo ProcessBuildInfo(const std::vector<LibraryVersion>& own_libraries) {
  BuildInfo build{.version = DcsVersion(), .libraries = ServiceLibraryVersions()};
  build.libraries.insert(build.libraries.end(), own_libraries.begin(), own_libraries.end());
  return build;
}

std::vector<LibraryVersion> ServiceLibraryVersions() {
  return {
      {"grpc", grpc::Version()},
      {"protobuf", google::protobuf::internal::VersionString(GOOGLE_PROTOBUF_VERSION)},
      {"abseil", absl::StrCat(ABSL_LTS_RELEASE_VERSION, ".", ABSL_LTS_RELEASE_PATCH_LEVEL)},
      // Neither has a version macro; CMake passes the versions it found.
      {"prometheus-cpp", DCS_PROMETHEUS_CPP_VERSION},
      {"yaml-cpp", DCS_YAML_CPP_VERSION},
      {"cpp-httplib", CPPHTTPLIB_VERSION},
  };
}

LibraryVersion CompiledLibtorchVersion() { return {"libtorch", DCS_LIBTORCH_VERSION}; }

}  // namespace dcs::services
