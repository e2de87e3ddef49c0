// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_TESTING_TEMP_DIR_H_
#define DCS_TESTS_TESTING_TEMP_DIR_H_

// Temporary directories for tests, under ::testing::TempDir(): one made on demand, or a
// fixture that gives every test a fresh one. Thread-compatible.

#include <filesystem>
#include <string>

#include "gtest/gtest.h"

namespace dcs::testing {

// A new empty directory, left with the test's temporary files. Fails the test (non-fatally)
// if it cannot be made.
std::string MakeTempDir();

// A fixture whose every test starts with a new empty directory, dir(), removed after it.
// A subclass that overrides SetUp or TearDown calls these first.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  const std::filesystem::path& dir() const { return dir_; }

  // `name` (a relative path) in dir().
  std::string Path(const std::string& name) const;

  // Writes `contents` to Path(name) with a plain ofstream (not atomically); returns the path.
  std::string WritePlain(const std::string& name, const std::string& contents) const;

 private:
  std::filesystem::path dir_;
};

}  // namespace dcs::testing

#endif  // DCS_TESTS_TESTING_TEMP_DIR_H_
