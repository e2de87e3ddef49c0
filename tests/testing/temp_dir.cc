// Copyright 2026 The DCS Authors.
#include "tests/testing/temp_dir.h"

#include <stdlib.h>

#include <fstream>

namespace dcs::testing {

std::string MakeTempDir() {
  std::string pattern = (std::filesystem::path(::testing::TempDir()) / "dcs-XXXXXX").string();
  const char* dir = ::mkdtemp(pattern.data());
  EXPECT_NE(dir, nullptr) << "mkdtemp " << pattern;
  return pattern;
}

void TempDirTest::SetUp() {
  dir_ = MakeTempDir();
  ASSERT_TRUE(std::filesystem::is_directory(dir_)) << dir_;
}

void TempDirTest::TearDown() {
  if (!dir_.empty()) std::filesystem::remove_all(dir_);
}

std::string TempDirTest::Path(const std::string& name) const { return (dir_ / name).string(); }

std::string TempDirTest::WritePlain(const std::string& name, const std::string& contents) const {
  const std::string path = Path(name);
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

}  // namespace dcs::testing
