// Copyright 2026 The DCS Authors.
#include "coordinator/run_submission.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator {
namespace {

using ::testing::HasSubstr;

constexpr char kConfig[] = R"(env: cartpole
seed: 3
total_timesteps: 2048
feature: length
training_range: [0.35, 0.75]
evaluation: {freq: 1024, episodes: 2, contexts: {id: [0.5]}}
)";

TEST(RunSubmissionTest, AppliesTheSeed) {
  absl::StatusOr<run::RunRequest> request = CheckSubmittedRun(kConfig, "run.yaml", 9);
  ASSERT_TRUE(request.ok()) << request.status();
  EXPECT_EQ(request->spec.seed, 9u);
  EXPECT_THAT(request->config_text, HasSubstr("seed: 9"));
  EXPECT_EQ(CheckSubmittedRun(kConfig, "run.yaml", std::nullopt)->spec.seed, 3u);
}

TEST(RunSubmissionTest, NamesTheFieldAndLineOfAnError) {
  const absl::Status status =
      CheckSubmittedRun("env: cartpole\nseed: 3\ntotal_timesteps: -5\n", "bad.yaml", std::nullopt)
          .status();
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(status.message(), HasSubstr("bad.yaml: total_timesteps: line 3"));
}

TEST(RunSubmissionTest, RefusesWhatTheEnvironmentCannotCarryOut) {
  std::string config = kConfig;
  config.replace(config.find("feature: length"), 15, "feature: warp");
  EXPECT_THAT(CheckSubmittedRun(config, "run.yaml", std::nullopt).status().message(),
              HasSubstr("warp"));
  config = kConfig;
  config.replace(config.find("cartpole"), 8, "pong");
  EXPECT_THAT(CheckSubmittedRun(config, "run.yaml", std::nullopt).status().message(),
              HasSubstr("pong"));
}

}  // namespace
}  // namespace dcs::coordinator
