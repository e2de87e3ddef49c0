// Copyright 2026 The DCS Authors.
#include "common/atomic_file.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::common {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

class AtomicFileTest : public dcs::testing::TempDirTest {
 protected:
  // Names of the entries in the test's directory, sorted.
  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir())) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }
};

TEST_F(AtomicFileTest, RoundTripsWithReadFile) {
  const std::string path = Path("state.yaml");
  ASSERT_TRUE(WriteFileAtomically(path, "grpc_port: 1234\n").ok());
  const absl::StatusOr<std::string> read = ReadFile(path);
  ASSERT_TRUE(read.ok()) << read.status();
  EXPECT_EQ(*read, "grpc_port: 1234\n");
}

TEST_F(AtomicFileTest, RoundTripsBinaryAndEmptyContents) {
  const std::string path = Path("blob");
  const std::string binary("a\0b\n\xff\x01", 6);
  ASSERT_TRUE(WriteFileAtomically(path, binary).ok());
  EXPECT_EQ(ReadFile(path).value_or("<error>"), binary);

  ASSERT_TRUE(WriteFileAtomically(path, "").ok());
  EXPECT_EQ(ReadFile(path).value_or("<error>"), "");
}

TEST_F(AtomicFileTest, ReplacesExistingFile) {
  const std::string path = Path("state.yaml");
  WritePlain("state.yaml", "a much longer old content that must not survive as a tail\n");
  ASSERT_TRUE(WriteFileAtomically(path, "new\n").ok());
  EXPECT_EQ(ReadFile(path).value_or("<error>"), "new\n");
}

TEST_F(AtomicFileTest, LeavesNoTemporaryFileBehind) {
  ASSERT_TRUE(WriteFileAtomically(Path("a"), "1").ok());
  ASSERT_TRUE(WriteFileAtomically(Path("a"), "2").ok());
  ASSERT_TRUE(WriteFileAtomically(Path("b"), "3").ok());
  EXPECT_THAT(Entries(), ElementsAre("a", "b"));
}

TEST_F(AtomicFileTest, RelativePathInCurrentDirectory) {
  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(dir());
  const absl::Status status = WriteFileAtomically("relative.txt", "here");
  std::filesystem::current_path(previous);
  ASSERT_TRUE(status.ok()) << status;
  EXPECT_EQ(ReadFile(Path("relative.txt")).value_or("<error>"), "here");
  EXPECT_THAT(Entries(), ElementsAre("relative.txt"));
}

TEST_F(AtomicFileTest, MissingDirectoryIsNotFoundAndNamesThePath) {
  const std::string path = Path("missing/state.yaml");
  const absl::Status status = WriteFileAtomically(path, "x");
  EXPECT_EQ(status.code(), absl::StatusCode::kNotFound) << status;
  EXPECT_THAT(status.message(), HasSubstr(path));
  EXPECT_THAT(Entries(), ElementsAre());
}

TEST_F(AtomicFileTest, FileInPlaceOfDirectoryIsNotFoundAndLeavesItUntouched) {
  // "parent" is a regular file, so "parent/child" has no directory to go in (ENOTDIR).
  const std::string parent = Path("parent");
  WritePlain("parent", "old contents\n");
  const absl::Status status = WriteFileAtomically(Path("parent/child"), "x");
  EXPECT_EQ(status.code(), absl::StatusCode::kNotFound) << status;
  EXPECT_EQ(ReadFile(parent).value_or("<error>"), "old contents\n");
  EXPECT_THAT(Entries(), ElementsAre("parent"));
}

TEST_F(AtomicFileTest, FailedRenameKeepsTargetAndRemovesTemporaryFile) {
  // The target is a non-empty directory: the temporary file is written, but cannot be renamed
  // over it.
  const std::string target = Path("occupied");
  std::filesystem::create_directory(target);
  WritePlain("occupied/keep", "old contents\n");

  const absl::Status status = WriteFileAtomically(target, "new contents\n");
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(target));
  EXPECT_EQ(ReadFile(Path("occupied/keep")).value_or("<error>"), "old contents\n");
  EXPECT_THAT(Entries(), ElementsAre("occupied"));
}

TEST_F(AtomicFileTest, ReadFileOfMissingFileIsNotFound) {
  const std::string path = Path("absent");
  const absl::StatusOr<std::string> read = ReadFile(path);
  EXPECT_EQ(read.status().code(), absl::StatusCode::kNotFound) << read.status();
  EXPECT_THAT(read.status().message(), HasSubstr(path));
}

}  // namespace
}  // namespace dcs::common
