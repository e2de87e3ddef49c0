// Copyright 2026 The DCS Authors.
#include "services/build_info.h"

#include <torch/version.h>

#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::MatchesRegex;

std::vector<std::string> Names(const std::vector<LibraryVersion>& libraries) {
  std::vector<std::string> names;
  for (const LibraryVersion& library : libraries) names.push_back(library.name);
  return names;
}

TEST(DcsVersionTest, IsReleasePlusCommit) {
  EXPECT_THAT(DcsVersion(), MatchesRegex("[0-9]+\\.[0-9]+\\.[0-9]+\\+[0-9A-Za-z]+"));
}

TEST(ServiceLibraryVersionsTest, ListsThePlumbingLibrariesWithVersions) {
  const std::vector<LibraryVersion> libraries = ServiceLibraryVersions();
  EXPECT_EQ(Names(libraries),
            (std::vector<std::string>{"grpc", "protobuf", "abseil", "prometheus-cpp", "yaml-cpp",
                                      "cpp-httplib"}));
  for (const LibraryVersion& library : libraries) {
    // Every version is dotted numbers (abseil's is its LTS date and patch level).
    EXPECT_THAT(library.version, MatchesRegex("[0-9]+(\\.[0-9]+)+.*")) << library.name;
  }
}

// What the programs without libtorch say of it is what those with it were compiled against.
TEST(CompiledLibtorchVersionTest, IsTheVersionOfTheHeadersTheTrainersCompileWith) {
  const LibraryVersion libtorch = CompiledLibtorchVersion();
  EXPECT_EQ(libtorch.name, "libtorch");
  EXPECT_EQ(libtorch.version, TORCH_VERSION);
}

TEST(ProcessBuildInfoTest, PlumbingLibrariesFirstThenOwn) {
  const BuildInfo build = ProcessBuildInfo({{"libtorch", "1.13.1"}, {"box2d", "2.4.1"}});
  EXPECT_EQ(build.version, DcsVersion());
  EXPECT_EQ(Names(build.libraries),
            (std::vector<std::string>{"grpc", "protobuf", "abseil", "prometheus-cpp", "yaml-cpp",
                                      "cpp-httplib", "libtorch", "box2d"}));
  for (const LibraryVersion& library : build.libraries) {
    EXPECT_FALSE(library.version.empty()) << library.name;
  }
  EXPECT_EQ(build.libraries[6].version, "1.13.1");
  EXPECT_EQ(build.libraries[7].version, "2.4.1");
}

TEST(ProcessBuildInfoTest, NoOwnLibraries) {
  EXPECT_EQ(ProcessBuildInfo({}).libraries, ServiceLibraryVersions());
}

}  // namespace
}  // namespace dcs::services
