// Copyright 2026 The DCS Authors.
//
// Study sweep specs (coordinator/study_sweep_spec.h): the study block read whole, defaults, and
// every bad block refused with its path and line.

#include "coordinator/study_sweep_spec.h"

#include <string>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/study_config.h"
#include "tests/run/source_files.h"

namespace dcs::coordinator {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kBase[] = R"(seeds: 2
observe: [live]
env: cartpole
evaluation: {contexts: {id: [0.5]}}
conditions:
  - name: base
    stages:
      - {steps: 1000, schedule: {family: constant}}
      - {steps: 1000, schedule: {family: constant}}
)";

constexpr char kSpace[] = R"(  space:
    parameters:
      - {name: "stages[0].schedule.family", type: categorical, choices: [constant, sinusoidal]}
      - {name: "stages[0].schedule.period", type: int, low: 25, high: 500, log: true,
         when: {"stages[0].schedule.family": sinusoidal}}
)";

std::string Spec(const std::string& study) {
  return absl::StrCat(kBase, "study:\n", study, kSpace);
}

absl::Status Error(const std::string& text) {
  return ParseStudySweepYaml(text, "search.yaml").status();
}

TEST(StudySweepSpecTest, ReadsTheBlockWithItsDefaults) {
  absl::StatusOr<StudySweepSpec> spec = ParseStudySweepYaml(Spec("  trials: 30\n"), "s.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->trials, 30);
  EXPECT_EQ(spec->parallel, 1);
  EXPECT_EQ(spec->objective, StudyObjective::kBestAnytime);
  EXPECT_EQ(spec->study.sampler, SamplerKind::kTpe);
  EXPECT_EQ(spec->study.seed, 0u);
  EXPECT_EQ(spec->study.direction, Direction::kMaximize);
  EXPECT_EQ(spec->study.tpe.startup_trials, 10);
  EXPECT_EQ(spec->study.pruner.kind, PrunerKind::kNone);
  EXPECT_EQ(spec->retrain_top_k, 0);
  ASSERT_EQ(spec->space.parameters.size(), 2u);
  EXPECT_THAT(spec->study.space, HasSubstr("stages[0].schedule.period"));
  EXPECT_THAT(spec->sweep.seeds, ElementsAre(0, 1));
}

TEST(StudySweepSpecTest, ReadsEveryOption) {
  absl::StatusOr<StudySweepSpec> spec = ParseStudySweepYaml(
      Spec("  trials: 30\n  parallel: 4\n  sampler: random\n  seed: 9\n"
           "  tpe: {startup_trials: 3, ei_candidates: 12, multivariate: true, group: true,\n"
           "        constant_liar: true}\n"
           "  objective: last_iqm\n"
           "  pruner: {kind: successive_halving, min_resource: 1000, reduction_factor: 3}\n"
           "  retrain: {top_k: 5, seeds: [10, 11, 12]}\n"),
      "s.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->parallel, 4);
  EXPECT_EQ(spec->study.sampler, SamplerKind::kRandom);
  EXPECT_EQ(spec->study.seed, 9u);
  EXPECT_EQ(spec->study.tpe.ei_candidates, 12);
  EXPECT_TRUE(spec->study.tpe.parzen.multivariate);
  EXPECT_TRUE(spec->study.tpe.constant_liar);
  EXPECT_EQ(spec->objective, StudyObjective::kLastIqm);
  EXPECT_EQ(spec->study.pruner.kind, PrunerKind::kSuccessiveHalving);
  EXPECT_EQ(spec->study.pruner.halving.min_resource, 1000);
  EXPECT_EQ(spec->study.pruner.halving.reduction_factor, 3);
  EXPECT_EQ(spec->retrain_top_k, 5);
  EXPECT_THAT(spec->retrain_seeds, ElementsAre(10, 11, 12));
}

TEST(StudySweepSpecTest, RetrainSeedsFollowTheSearchs) {
  absl::StatusOr<StudySweepSpec> spec =
      ParseStudySweepYaml(Spec("  trials: 3\n  retrain: {top_k: 2, seeds: 3}\n"), "s.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_THAT(spec->retrain_seeds, ElementsAre(2, 3, 4));
}

TEST(StudySweepSpecTest, RefusesABadBlockNamingWhere) {
  EXPECT_THAT(Error(Spec("  parallel: 2\n")).message(),
              HasSubstr("study: line 11: missing 'trials'"));
  EXPECT_THAT(Error(Spec("  trials: 0\n")).message(),
              HasSubstr("study.trials: line 11: must be at least 1"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  sampler: cmaes\n")).message(),
              HasSubstr("study.sampler: line 12: must be tpe or random, got 'cmaes'"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  budget: 9\n")).message(), HasSubstr("budget"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  objective: mean\n")).message(),
              HasSubstr("must be best_anytime or last_iqm, got 'mean'"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  pruner: {percentile: 20}\n")).message(),
              HasSubstr("study.pruner: line 12: missing 'kind'"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  pruner: {kind: median, percentile: 120}\n")).message(),
              HasSubstr("percentile in [0, 100]"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  tpe: {group: true}\n")).message(),
              HasSubstr("group option needs multivariate"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  retrain: {top_k: 2, seeds: [5, 1]}\n")).message(),
              HasSubstr("study.retrain.seeds[1]: line 12: seed 1 is one of the search's"));
  EXPECT_THAT(Error(Spec("  trials: 3\n  retrain: {top_k: 2}\n")).message(),
              HasSubstr("a retrain gives top_k and seeds"));
  EXPECT_THAT(Error(absl::StrCat(kBase, "study:\n  trials: 3\n")).message(),
              HasSubstr("missing 'space'"));
  EXPECT_THAT(Error(absl::StrCat(kBase, "study: [3]\n")).message(),
              HasSubstr("study: line 10: must be a mapping"));
}

TEST(StudySweepSpecTest, RefusesASpaceThatMakesBadRunConfigs) {
  // A period for a constant schedule: some samples write a key a constant schedule lacks.
  const std::string text = absl::StrReplaceAll(
      Spec("  trials: 3\n"), {{R"(when: {"stages[0].schedule.family": sinusoidal})", "step: 1"}});
  EXPECT_THAT(Error(text).message(),
              HasSubstr("study.space: a sample of the space makes a run config that does not "
                        "validate"));
  // A name that is not a key path.
  EXPECT_THAT(
      Error(absl::StrReplaceAll(Spec("  trials: 3\n"),
                                {{"\"stages[0].schedule.period\"", "\"stages[0]..x\""},
                                 {"when: {\"stages[0].schedule.family\": sinusoidal}", "step: 1"}}))
          .message(),
      HasSubstr("study.space"));
}

TEST(StudySweepSpecTest, AStudySearchesOneConditionInOneMode) {
  std::string text =
      absl::StrReplaceAll(Spec("  trials: 3\n"), {{"observe: [live]", "observe: [none, live]"}});
  EXPECT_THAT(Error(text).message(),
              HasSubstr("a study searches one condition in one observation mode; the spec has 2"));
  EXPECT_THAT(Error(kBase).message(), HasSubstr("study: missing"));
}

// Every study sweep in configs/ reads whole; the paper's CartPole search makes a valid run
// config with every stage in each of its modes.
TEST(StudySweepSpecTest, TheStudiesInConfigsMakeValidRunConfigs) {
  int studies = 0;
  for (const run::ConfigFile& file : run::ConfigFiles()) {
    if (!absl::StrContains(file.text, "\nstudy:")) continue;
    const absl::StatusOr<StudySweepSpec> spec = ParseStudySweepYaml(file.text, file.path.string());
    ASSERT_TRUE(spec.ok()) << spec.status();
    ++studies;
    if (file.path.filename() != "cartpole_multistage_search.yaml") continue;
    EXPECT_EQ(spec->trials, 240);
    EXPECT_EQ(spec->sweep.seeds.size(), 4u);
    EXPECT_EQ(spec->retrain_top_k, 20);
    EXPECT_EQ(spec->retrain_seeds.size(), 10u);
    for (const double mode : {0, 1, 2}) {  // constant, sinusoidal, cosine annealing
      run::ParameterValues values;
      for (int stage = 0; stage < 4; ++stage) {
        const std::string schedule = absl::StrCat("stages[", stage, "].schedule.");
        values[schedule + "family"] = mode;
        if (mode == 1) {
          values[schedule + "amplitude_frac"] = 0.3;
          values[schedule + "period"] = 150;
        }
        if (mode == 2) {
          values[schedule + "neighborhood_radius_frac"] = 0.2;
          values[schedule + "T_0"] = 250;
        }
      }
      const absl::StatusOr<run::SeededRuns> config =
          run::TrialRunConfig(spec->sweep.trials.front().config, "base", spec->space, values);
      EXPECT_TRUE(config.ok()) << "mode " << mode << ": " << config.status();
    }
  }
  EXPECT_EQ(studies, 2);
}

}  // namespace
}  // namespace dcs::coordinator
