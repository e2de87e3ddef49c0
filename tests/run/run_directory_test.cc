// Copyright 2026 The DCS Authors.
#include "run/run_directory.h"

#include <filesystem>
#include <string>

#include "absl/strings/str_replace.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

namespace dcs::run {
namespace {

using ::testing::HasSubstr;

constexpr char kConfig[] = R"(# the paper's setting
env: cartpole
seed: 3
feature: length
evaluation: {contexts: {id: [0.5]}}
)";

class RunDirectoryTest : public testing::TempDirTest {};

TEST_F(RunDirectoryTest, NewRunGoesToItsDefaultDirectoryNamedAfterConfigAndSeed) {
  absl::StatusOr<RunRequest> request =
      RequestRun(kConfig, "configs/tiny.yaml", "", Path("data"));
  ASSERT_TRUE(request.ok()) << request.status();
  EXPECT_EQ(request->dir, Path("data/runs/tiny-seed3"));
  EXPECT_EQ(request->spec.seed, 3u);
  EXPECT_TRUE(CheckNewRun(*request).ok());
  ASSERT_TRUE(CreateRunDirectory(*request).ok());
  EXPECT_EQ(ReadFile(Path("data/runs/tiny-seed3/config.yaml")).value_or(""), kConfig);

  const absl::Status again = CheckNewRun(*request);
  EXPECT_EQ(again.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(again.message(), HasSubstr("already holds a run"));
  EXPECT_TRUE(CheckResumedRun(*request, "tiny.yaml").ok());
}

TEST_F(RunDirectoryTest, SeedOverrideIsStoredAndNamesTheDirectory) {
  const std::string with_seed = ConfigWithSeed(kConfig, 11);
  EXPECT_THAT(with_seed, HasSubstr("seed: 11"));
  absl::StatusOr<RunRequest> request = RequestRun(with_seed, "tiny.yaml", "", Path("data"));
  ASSERT_TRUE(request.ok()) << request.status();
  EXPECT_EQ(request->spec.seed, 11u);
  EXPECT_EQ(request->dir, Path("data/runs/tiny-seed11"));
  // Not a mapping: left as is, for the parser to report.
  EXPECT_EQ(ConfigWithSeed("- 1\n", 11), "- 1\n");
  EXPECT_EQ(ConfigWithSeed("a: [1\n", 11), "a: [1\n");
}

TEST_F(RunDirectoryTest, ResumeNeedsTheStoredRunOfTheSameConfig) {
  absl::StatusOr<RunRequest> request = RequestRun(kConfig, "tiny.yaml", Path("run"), "");
  ASSERT_TRUE(request.ok()) << request.status();
  EXPECT_EQ(CheckResumedRun(*request, "tiny.yaml").code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(StoredRun(Path("run")).status().code(), absl::StatusCode::kNotFound);
  ASSERT_TRUE(CreateRunDirectory(*request).ok());

  absl::StatusOr<RunRequest> stored = StoredRun(Path("run"));
  ASSERT_TRUE(stored.ok()) << stored.status();
  EXPECT_EQ(stored->config_text, kConfig);
  EXPECT_EQ(stored->dir, Path("run"));

  absl::StatusOr<RunRequest> other =
      RequestRun(ConfigWithSeed(kConfig, 4), "tiny.yaml", Path("run"), "");
  ASSERT_TRUE(other.ok());
  const absl::Status refused = CheckResumedRun(*other, "tiny.yaml with --seed");
  EXPECT_EQ(refused.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_THAT(refused.message(), HasSubstr("differs from tiny.yaml with --seed"));
}

TEST_F(RunDirectoryTest, BadConfigsAndDirectoriesAreNamed) {
  EXPECT_THAT(RequestRun(absl::StrReplaceAll(kConfig, {{"env: cartpole", "env: cartpol"}}),
                         "bad.yaml", "", "")
                  .status()
                  .message(),
              HasSubstr("bad.yaml: env: line 2: unknown environment 'cartpol'"));
  WritePlain("file", "not a directory");
  absl::StatusOr<RunRequest> request = RequestRun(kConfig, "tiny.yaml", Path("file/run"), "");
  ASSERT_TRUE(request.ok());
  const absl::Status status = CreateRunDirectory(*request);
  EXPECT_FALSE(status.ok());
  EXPECT_THAT(status.message(), HasSubstr(Path("file/run")));
}

}  // namespace
}  // namespace dcs::run
