// Copyright 2026 The DCS Authors.
//
// README's walk-through (its "Step by step" section), run as it is written, as a newcomer
// would: in a fresh directory holding the repository's configs/, with this build's programs on
// PATH. Every command must succeed, and what the section says they leave must be there.

#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/integration/test_util.h"
#include "tests/testing/scoped_variable.h"
#include "tests/testing/slowdown.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

using ::testing::HasSubstr;
using ::dcs::testing::ScopedVariable;

// The shell block that follows README's walk-through marker, or "" if there is none.
std::string WalkthroughBlock(const std::string& readme) {
  constexpr std::string_view kMarker = "tests/integration/walkthrough_test.cc runs this block";
  constexpr std::string_view kOpen = "```sh\n";
  const size_t marker = readme.find(kMarker);
  if (marker == std::string::npos) return "";
  const size_t open = readme.find(kOpen, marker);
  if (open == std::string::npos) return "";
  const size_t begin = open + kOpen.size();
  const size_t end = readme.find("```", begin);
  return end == std::string::npos ? "" : readme.substr(begin, end - begin);
}

bool Exists(const std::string& path) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

TEST(WalkthroughTest, ReadmesStepByStepRunsAsWritten) {
  const absl::StatusOr<std::string> readme = ReadFile(DCS_SOURCE_DIR "/README.md");
  ASSERT_TRUE(readme.ok()) << readme.status();
  const std::string block = WalkthroughBlock(*readme);
  ASSERT_THAT(block, HasSubstr("dcs eval")) << "README's walk-through block";

  const std::string dir = testing::MakeTempDir();
  std::filesystem::create_directory_symlink(DCS_SOURCE_DIR "/configs", dir + "/configs");
  const char* path = std::getenv("PATH");
  const ScopedVariable programs("PATH", absl::StrCat(BinDir(), ":", path == nullptr ? "" : path));
  const ScopedVariable no_data_dir("DCS_DATA_DIR", std::nullopt);
  const ScopedVariable no_addr("DCS_ADDR", std::nullopt);
  const RunResult walkthrough = RunProgram(
      "/bin/sh", {"-c", absl::StrCat("set -ex\ncd '", dir, "'\n", block)},
      testing::Patient(absl::Minutes(10)));
  // A failed step leaves the cluster up: stop it (a no-op after the block's own `dcs down`).
  RunProgram(BinaryPath("dcs"), {"down", "--data-dir", dir + "/dcs-data"});
  ASSERT_EQ(walkthrough.exit_code, 0) << walkthrough.output;

  EXPECT_THAT(walkthrough.output, HasSubstr("completed, 18/18 runs done"));
  EXPECT_THAT(walkthrough.output, HasSubstr("IQM [Q1, Q3]"));
  EXPECT_THAT(walkthrough.output, HasSubstr("cluster stopped"));
  const std::string reports = dir + "/dcs-data/reports";
  EXPECT_TRUE(Exists(reports + "/sweep-1/index.html"));
  EXPECT_TRUE(Exists(reports + "/sweep-1/family_heatmap.svg"));
  EXPECT_TRUE(Exists(reports + "/generalisation/cells.csv"));
  EXPECT_TRUE(Exists(reports + "/generalisation/generalization.png"));
}

}  // namespace
}  // namespace dcs::integration
