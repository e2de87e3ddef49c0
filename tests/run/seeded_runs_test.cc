// Copyright 2026 The DCS Authors.
//
// SeededRuns: each seed's run of a config read once is the run RequestRun makes of
// ConfigWithSeed's text, byte for byte (a run's stored config must not change), for every trial
// of every sweep in configs/.

#include "run/seeded_runs.h"

#include <cstdint>
#include <limits>
#include <string>

#include "absl/strings/str_cat.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_directory.h"
#include "run/run_spec_yaml.h"
#include "run/sweep_spec_yaml.h"
#include "tests/run/source_files.h"

namespace dcs::run {
namespace {

constexpr uint64_t kSeeds[] = {0, 7, 39, std::numeric_limits<uint64_t>::max()};

// Each seed's run of `runs` against RequestRun on ConfigWithSeed of `text`.
void ExpectRunsAsRequested(SeededRuns runs, const std::string& text,
                           const std::string& where) {
  for (uint64_t seed : kSeeds) {
    const RunRequest run = runs.Run(seed);
    absl::StatusOr<RunRequest> requested = RequestRun(ConfigWithSeed(text, seed), where, "-", "");
    ASSERT_TRUE(requested.ok()) << requested.status();
    EXPECT_EQ(run.config_text, requested->config_text) << where << " seed " << seed;
    EXPECT_EQ(run.spec.seed, seed);
    EXPECT_EQ(requested->spec.seed, seed);
    // The spec carried is the one the text reads as (its YAML, field by field, is the same).
    EXPECT_EQ(run.spec.env, requested->spec.env);
    EXPECT_EQ(run.spec.total_timesteps, requested->spec.total_timesteps);
    EXPECT_EQ(run.spec.observe, requested->spec.observe);
    EXPECT_EQ(run.spec.pool_values, requested->spec.pool_values);
    ASSERT_EQ(run.spec.stages.size(), requested->spec.stages.size());
    for (size_t k = 0; k < run.spec.stages.size(); ++k) {
      EXPECT_EQ(run.spec.stages[k].steps, requested->spec.stages[k].steps);
      EXPECT_EQ(run.spec.stages[k].schedule.params, requested->spec.stages[k].schedule.params);
    }
    EXPECT_EQ(run.spec.ppo.n_steps, requested->spec.ppo.n_steps);
    EXPECT_TRUE(run.dir.empty());
  }
}

TEST(SeededRunsTest, EverySweepTrialsRunsAreTheRunsOfItsConfigWithTheSeed) {
  int trials = 0;
  for (const ConfigFile& file : ConfigFiles()) {
    if (file.kind != ConfigFile::Kind::kSweep) continue;
    absl::StatusOr<SweepSpec> spec = ParseSweepSpecYaml(file.text, file.path.string());
    ASSERT_TRUE(spec.ok()) << spec.status();
    for (const SweepTrial& trial : spec->trials) {
      ExpectRunsAsRequested(SeededRuns(trial.spec, trial.config), trial.config,
                            absl::StrCat(file.path.string(), ": ", trial.condition));
      ++trials;
    }
  }
  EXPECT_GT(trials, 100);
}

// A config of its own seed (`dcs submit-run --seed`) gets the new one where the old one stood.
TEST(SeededRunsTest, AConfigWithASeedHasItReplaced) {
  const std::string text = R"(env: cartpole
seed: 3
feature: length
training_range: [0.35, 0.75]
evaluation: {contexts: {id: [0.5]}}
)";
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(text, "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  SeededRuns runs(*spec, text);
  ExpectRunsAsRequested(runs, text, "run.yaml");
  EXPECT_THAT(runs.Run(9).config_text, ::testing::HasSubstr("seed: 9\nfeature: length"));
}

}  // namespace
}  // namespace dcs::run
