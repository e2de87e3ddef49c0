// Copyright 2026 The DCS Authors.
//
// PPO with SB3's defaults learns standard CartPole-v1 (configs/cartpole_default_static.yaml):
// every one of 5 seeds reaches a deterministic mean return of at least 475 by 150k steps. The
// real `dcs train`, end to end; about a minute of one core.

#include <algorithm>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "dcs/v1/evaluation.pb.h"
#include "gtest/gtest.h"
#include "run/evaluation_log.h"
#include "tests/integration/test_util.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

TEST(TrainingQualityTest, EverySeedBalancesStandardCartPoleBy150kSteps) {
  const std::string dir = testing::MakeTempDir();
  for (int seed = 0; seed < 5; ++seed) {
    const std::string out = absl::StrCat(dir, "/seed", seed);
    const RunResult train = RunProgram(
        BinaryPath("dcs"),
        {"train", "--config", absl::StrCat(DCS_SOURCE_DIR, "/configs/cartpole_default_static.yaml"),
         "--seed", absl::StrCat(seed), "--out", out},
        absl::Minutes(5));
    ASSERT_EQ(train.exit_code, 0) << train.output;

    const absl::StatusOr<v1::EvaluationLog> log = run::ReadEvaluationLog(out);
    ASSERT_TRUE(log.ok()) << log.status();
    double best = 0;
    for (const v1::Evaluation& evaluation : log->evaluations()) {
      if (evaluation.step() <= 150'000) best = std::max(best, evaluation.avg_combined());
    }
    EXPECT_GE(best, 475) << "seed " << seed;
  }
}

}  // namespace
}  // namespace dcs::integration
