// Copyright 2026 The DCS Authors.
#include "run/sweep_spec_yaml.h"

#include <algorithm>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "common/enum_names.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "run/run_spec_yaml.h"
#include "tests/run/source_files.h"

namespace dcs::run {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::Pair;
using ::testing::StartsWith;
using ::testing::UnorderedElementsAre;
using enum actor::Split;

// A valid CartPole sweep's keys but its conditions (which start on line 21); tests change one
// thing in it.
constexpr char kBase[] = R"(seeds: 2
observe: [none, live]
env: cartpole
total_timesteps: 150000
feature: length
training_range: [0.35, 0.75]
pool: {size: 7}
context: {masspole: 0.1}
evaluation:
  freq: 10000
  episodes: 30
  contexts:
    id: [0.4, 0.5]
    ood_low: [0.06, 0.12]
    ood_high: [0.92, 1.32]
ppo:
  learning_rate: 3.0e-4
  n_epochs: 10
  gamma: 0.99
conditions:
)";

// kBase with `conditions` (lines from 21 on), and `from` replaced by `to` in kBase.
std::string Spec(absl::string_view conditions, absl::string_view from = "",
                 absl::string_view to = "") {
  std::string base(kBase);
  if (!from.empty()) {
    EXPECT_TRUE(absl::StrContains(base, from)) << from;
    base = absl::StrReplaceAll(base, {{from, to}});
  }
  return absl::StrCat(base, conditions);
}

SweepSpec Parse(const std::string& text) {
  absl::StatusOr<SweepSpec> spec = ParseSweepSpecYaml(text, "sweep.yaml");
  EXPECT_TRUE(spec.ok()) << spec.status();
  return spec.ok() ? *std::move(spec) : SweepSpec();
}

// The error message of parsing `text`, or "OK".
std::string ErrorOf(const std::string& text) {
  absl::StatusOr<SweepSpec> spec = ParseSweepSpecYaml(text, "sweep.yaml");
  if (spec.ok()) return "OK";
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  return std::string(spec.status().message());
}

// Each trial as "condition | family | observe".
std::vector<std::string> Trials(const SweepSpec& spec) {
  std::vector<std::string> trials;
  for (const SweepTrial& trial : spec.trials) {
    trials.push_back(absl::StrCat(trial.condition, " | ", trial.family, " | ",
                                  NameOf(env::kObserveModeNames, trial.observe)));
  }
  return trials;
}

// The run config of `trial`, read back.
RunSpec RunOf(const SweepTrial& trial) {
  absl::StatusOr<RunSpec> run = ParseRunSpecYaml(trial.config, "trial.yaml");
  EXPECT_TRUE(run.ok()) << run.status() << "\n" << trial.config;
  return run.ok() ? *std::move(run) : RunSpec();
}

double Param(const RunSpec& run, size_t stage, const std::string& name) {
  const env::ScheduleParam& param = run.stages.at(stage).schedule.params.at(name);
  EXPECT_TRUE(std::holds_alternative<double>(param)) << name;
  return std::holds_alternative<double>(param) ? std::get<double>(param) : -1;
}

TEST(SweepSpecYamlTest, ExpandsConditionsInOrderEachInItsModes) {
  const SweepSpec spec = Parse(Spec(R"(  - name: static
  - schedule: {family: sinusoidal, period: 125}
    grid: {schedule.amplitude_frac: [0.25, 0.5]}
  - stages:
      - {steps: 30000, schedule: {family: constant}}
      - {steps: 120000, schedule: {family: cosine_annealing, T_0: 250}}
  - schedule: {family: constant}
)"));
  EXPECT_THAT(Trials(spec),
              ElementsAre("static | static | none", "static | static | live",
                          "sinusoidal amplitude_frac=0.25 | sinusoidal | none",
                          "sinusoidal amplitude_frac=0.25 | sinusoidal | live",
                          "sinusoidal amplitude_frac=0.5 | sinusoidal | none",
                          "sinusoidal amplitude_frac=0.5 | sinusoidal | live",
                          "constant>cosine_annealing | multi_stage | none",
                          "constant>cosine_annealing | multi_stage | live",
                          "constant | identity | none", "constant | identity | live"));
  EXPECT_THAT(spec.seeds, ElementsAre(0, 1));
  EXPECT_EQ(spec.baseline, "static");
  EXPECT_EQ(spec.name, "");
  EXPECT_EQ(RunOf(spec.trials[1]).observe, env::ObserveMode::kLive);
  EXPECT_EQ(Param(RunOf(spec.trials[4]), 0, "amplitude_frac"), 0.5);
  EXPECT_EQ(Param(RunOf(spec.trials[4]), 0, "period"), 125);

  EXPECT_EQ(Parse(absl::StrCat("name: small\n", Spec("  - {schedule: {family: constant}}\n")))
                .name,
            "small");
  EXPECT_EQ(Parse(Spec("  - {schedule: {family: constant}}\n")).baseline, std::nullopt);
}

TEST(SweepSpecYamlTest, GridIsTheCartesianProductWithTheLastKeyFastest) {
  const SweepSpec spec = Parse(Spec(R"(  - name: sin
    schedule: {family: sinusoidal}
    grid:
      schedule.amplitude_frac: [0.25, 0.5]
      schedule.period: [100, 2.0e2]
    observe: none
)"));
  EXPECT_THAT(Trials(spec),
              ElementsAre("sin amplitude_frac=0.25 period=100 | sinusoidal | none",
                          "sin amplitude_frac=0.25 period=2.0e2 | sinusoidal | none",
                          "sin amplitude_frac=0.5 period=100 | sinusoidal | none",
                          "sin amplitude_frac=0.5 period=2.0e2 | sinusoidal | none"));
  ASSERT_EQ(spec.trials.size(), 4u);
  const RunSpec second = RunOf(spec.trials[1]);
  EXPECT_EQ(Param(second, 0, "amplitude_frac"), 0.25);
  EXPECT_EQ(Param(second, 0, "period"), 200);
  EXPECT_EQ(Param(RunOf(spec.trials[2]), 0, "period"), 100);
}

TEST(SweepSpecYamlTest, GridReachesListItemsAndKeysTheConditionLacks) {
  // A key with list indices is written in a block mapping, or quoted: '[' ends a plain scalar
  // in a flow mapping.
  const SweepSpec spec = Parse(Spec(R"(  - stages:
      - {steps: 30000, schedule: {family: constant}}
      - {steps: 120000, schedule: {family: cosine_annealing, T_0: 250}}
    grid:
      stages[1].schedule.T_0: [100, 250]
      ppo.n_epochs: [5]
    observe: live
  - {name: small, grid: {"stages[0].steps": [5]}, pool: {size: 2},
     stages: [{steps: 10, schedule: {family: constant}}]}
)"));
  EXPECT_THAT(Trials(spec),
              ElementsAre("constant>cosine_annealing T_0=100 n_epochs=5 | multi_stage | live",
                          "constant>cosine_annealing T_0=250 n_epochs=5 | multi_stage | live",
                          "small steps=5 | identity | none", "small steps=5 | identity | live"));
  ASSERT_EQ(spec.trials.size(), 4u);
  const RunSpec first = RunOf(spec.trials[0]);
  EXPECT_EQ(Param(first, 1, "T_0"), 100);
  EXPECT_EQ(first.stages[0].steps, 30000);
  EXPECT_EQ(first.ppo.n_epochs, 5);
  EXPECT_EQ(first.ppo.gamma, 0.99);  // the base's other ppo keys stay
  EXPECT_EQ(first.pool_size, 7);
  // Placing a value copies what it changes: the spec's own stage is as written.
  EXPECT_EQ(Param(RunOf(spec.trials[1]), 1, "T_0"), 250);
  const RunSpec small = RunOf(spec.trials[2]);
  EXPECT_EQ(small.stages.at(0).steps, 5);
  EXPECT_EQ(small.pool_size, 2);
}

TEST(SweepSpecYamlTest, ConditionKeysReplaceTheBasesButContextEvaluationAndPpoMerge) {
  const SweepSpec spec = Parse(Spec(R"(  - name: changed
    ppo: {n_epochs: 5}
    pool: {values: [0.4, 0.5]}
    context: {masscart: 2.0}
    evaluation: {episodes: 5}
    total_timesteps: 50000
    observe: none
  - name: base
    observe: none
)"));
  ASSERT_EQ(spec.trials.size(), 2u);
  const RunSpec changed = RunOf(spec.trials[0]);
  EXPECT_EQ(changed.ppo.n_epochs, 5);
  EXPECT_EQ(changed.ppo.gamma, 0.99);
  EXPECT_EQ(changed.ppo.learning_rate, 3e-4);
  EXPECT_THAT(changed.pool_values, ElementsAre(0.4, 0.5));
  EXPECT_EQ(changed.pool_size, 1);  // the base's {size: 7} is replaced whole
  EXPECT_THAT(changed.context, UnorderedElementsAre(Pair("masspole", 0.1), Pair("masscart", 2.0)));
  EXPECT_EQ(changed.eval_episodes, 5);
  EXPECT_EQ(changed.eval_freq, 10000);
  EXPECT_THAT(changed.eval_values(kOodHigh), ElementsAre(0.92, 1.32));
  EXPECT_EQ(changed.total_timesteps, 50000);

  const RunSpec base = RunOf(spec.trials[1]);
  EXPECT_EQ(base.ppo.n_epochs, 10);
  EXPECT_EQ(base.pool_size, 7);
  EXPECT_TRUE(base.pool_values.empty());
  EXPECT_THAT(base.context, UnorderedElementsAre(Pair("masspole", 0.1)));
  EXPECT_EQ(base.eval_episodes, 30);
  EXPECT_EQ(base.total_timesteps, 150000);
}

TEST(SweepSpecYamlTest, ModesComeFromTheSweepUnlessAConditionGivesItsOwn) {
  EXPECT_THAT(Trials(Parse(Spec(R"(  - name: a
  - name: b
    observe: [live, initial]
  - name: c
    observe: initial
)"))),
              ElementsAre("a | static | none", "a | static | live", "b | static | live",
                          "b | static | initial", "c | static | initial"));
  EXPECT_THAT(Trials(Parse(Spec("  - name: a\n", "observe: [none, live]", "observe: live"))),
              ElementsAre("a | static | live"));
  EXPECT_THAT(Trials(Parse(Spec("  - name: a\n", "observe: [none, live]\n", ""))),
              ElementsAre("a | static | none"));
}

TEST(SweepSpecYamlTest, SeedsAreACountOrAList) {
  EXPECT_THAT(Parse(Spec("  - name: a\n", "seeds: 2", "seeds: 3")).seeds, ElementsAre(0, 1, 2));
  EXPECT_THAT(Parse(Spec("  - name: a\n", "seeds: 2", "seeds: [0, 5, 7]")).seeds,
              ElementsAre(0, 5, 7));
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: 0")),
            "sweep.yaml: seeds: line 1: must be at least 1, got 0");
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: []")),
            "sweep.yaml: seeds: line 1: must list at least one seed");
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: [1, 5, 1]")),
            "sweep.yaml: seeds[2]: line 1: seed 1 is listed twice (also seeds[0])");
  EXPECT_THAT(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: [1, -5]")),
              AllOf(StartsWith("sweep.yaml: seeds[1]: line 1: "),
                    HasSubstr("non-negative integer")));
  EXPECT_THAT(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: {n: 2}")),
              StartsWith("sweep.yaml: seeds: line 1: must be a number of seeds"));
  EXPECT_THAT(ErrorOf(Spec("  - name: a\n", "seeds: 2\n", "")),
              StartsWith("sweep.yaml: seeds: missing"));
}

TEST(SweepSpecYamlTest, TheTrialConfigReadsAsTheRunConfigItStandsFor) {
  const SweepSpec spec = Parse(Spec(R"(  - ppo: {n_epochs: 5}
    schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}
)"));
  ASSERT_EQ(spec.trials.size(), 2u);
  const SweepTrial& trial = spec.trials[1];
  EXPECT_THAT(trial.config, AllOf(Not(HasSubstr("seed")), HasSubstr("3.0e-4"),
                                  Not(HasSubstr("conditions")), Not(HasSubstr("grid"))));
  // The same run, written by hand.
  absl::StatusOr<RunSpec> expected = ParseRunSpecYaml(R"(env: cartpole
total_timesteps: 150000
feature: length
training_range: [0.35, 0.75]
pool: {size: 7}
context: {masspole: 0.1}
schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}
observe: live
evaluation:
  freq: 10000
  episodes: 30
  contexts: {id: [0.4, 0.5], ood_low: [0.06, 0.12], ood_high: [0.92, 1.32]}
ppo: {learning_rate: 3.0e-4, n_epochs: 5, gamma: 0.99}
)",
                                                      "expected.yaml");
  ASSERT_TRUE(expected.ok()) << expected.status();
  const RunSpec run = RunOf(trial);
  EXPECT_EQ(run.env, expected->env);
  EXPECT_EQ(run.seed, 0u);
  EXPECT_EQ(run.total_timesteps, expected->total_timesteps);
  EXPECT_EQ(run.n_envs, expected->n_envs);
  EXPECT_EQ(run.context, expected->context);
  EXPECT_EQ(run.feature, expected->feature);
  EXPECT_EQ(run.range_lo, expected->range_lo);
  EXPECT_EQ(run.range_hi, expected->range_hi);
  EXPECT_EQ(run.pool_size, expected->pool_size);
  EXPECT_EQ(run.pool_values, expected->pool_values);
  ASSERT_EQ(run.stages.size(), 1u);
  EXPECT_EQ(run.stages[0].steps, expected->stages[0].steps);
  EXPECT_EQ(run.stages[0].schedule.family, expected->stages[0].schedule.family);
  EXPECT_EQ(run.stages[0].schedule.params, expected->stages[0].schedule.params);
  EXPECT_EQ(run.observe, expected->observe);
  EXPECT_EQ(run.eval_freq, expected->eval_freq);
  EXPECT_EQ(run.eval_episodes, expected->eval_episodes);
  EXPECT_EQ(run.eval_contexts, expected->eval_contexts);
  EXPECT_EQ(run.ppo.learning_rate, expected->ppo.learning_rate);
  EXPECT_EQ(run.ppo.n_epochs, expected->ppo.n_epochs);
  EXPECT_EQ(run.ppo.gamma, expected->ppo.gamma);
  EXPECT_EQ(run.ppo.n_steps, expected->ppo.n_steps);
}

TEST(SweepSpecYamlTest, MalformedYamlIsReportedAloneWithItsLine) {
  EXPECT_THAT(ErrorOf("seeds: 2\n  bad: indentation\n"),
              AllOf(StartsWith("sweep.yaml: line 2, column"), Not(HasSubstr("problems"))));
  EXPECT_THAT(ErrorOf(Spec("  - {name: a\n")), StartsWith("sweep.yaml: line "));
  EXPECT_THAT(ErrorOf(""), HasSubstr("must be a sweep spec"));
  EXPECT_THAT(ErrorOf("- name: a\n"), HasSubstr("must be a sweep spec"));
}

TEST(SweepSpecYamlTest, TopLevelKeysAreTheSweepsAndTheBasesOnly) {
  EXPECT_EQ(ErrorOf(Spec("  - name: a\nfoo: 1\n")),
            "sweep.yaml: foo: line 22: unknown key 'foo' at the top level (allowed: name, seeds, "
            "observe, conditions, env, total_timesteps, n_envs, context, feature, "
            "training_range, pool, evaluation, ppo, coverage, study)");
  EXPECT_THAT(ErrorOf(Spec("  - name: a\nseed: 4\n")),
              StartsWith("sweep.yaml: seed: line 22: a sweep gives 'seeds'"));
  EXPECT_THAT(ErrorOf(Spec("  - name: a\nschedule: {family: constant}\n")),
              StartsWith("sweep.yaml: schedule: line 22: 'schedule' belongs to a condition"));
  EXPECT_THAT(ErrorOf(Spec("  - name: a\nstages: []\n")),
              StartsWith("sweep.yaml: stages: line 22: 'stages' belongs to a condition"));
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n", "observe: [none, live]", "observe: [none, lve]")),
            "sweep.yaml: observe[1]: line 2: must be none, initial or live, got 'lve'");
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n", "observe: [none, live]", "observe: [live, live]")),
            "sweep.yaml: observe[1]: line 2: mode live is listed twice (also observe[0])");
}

TEST(SweepSpecYamlTest, ConditionKeysAreChecked) {
  EXPECT_EQ(ErrorOf(Spec("  - name: a\n    sed: 4\n")),
            "sweep.yaml: conditions[0].sed: line 22: unknown key 'sed' in conditions[0] (allowed: "
            "name, grid, observe, schedule, stages, env, total_timesteps, n_envs, context, "
            "feature, training_range, pool, evaluation, ppo, coverage)");
  EXPECT_THAT(ErrorOf(Spec("  - name: a\n    seed: 4\n")),
              StartsWith("sweep.yaml: conditions[0].seed: line 22: seeds are the sweep's"));
  EXPECT_THAT(ErrorOf(Spec("  - name: a/b\n")),
              StartsWith("sweep.yaml: conditions[0].name: line 21: a name may not hold '/'"));
  EXPECT_THAT(ErrorOf(Spec("  - name: \"a\\tb\"\n")),
              StartsWith("sweep.yaml: conditions[0].name: line 21: a name may not hold control"));
  EXPECT_THAT(ErrorOf(Spec("  - static\n")),
              StartsWith("sweep.yaml: conditions[0]: line 21: conditions[0] must be a condition"));
  EXPECT_THAT(ErrorOf(Spec(R"(  - schedule: {family: constant}
    stages: [{steps: 10, schedule: {family: constant}}]
)")),
              AllOf(StartsWith("sweep.yaml: conditions[0].stages: line 22: "),
                    HasSubstr("not both")));
}

TEST(SweepSpecYamlTest, ScheduleErrorsNameTheConditionsField) {
  EXPECT_THAT(ErrorOf(Spec("  - schedule: {family: wobble}\n")),
              StartsWith("sweep.yaml: conditions[0].schedule: line 21: unknown schedule family "
                         "'wobble' (known: constant, identity"));
  EXPECT_THAT(ErrorOf(Spec("  - schedule: {family: sinusoidal, wobble: 3}\n")),
              AllOf(StartsWith("sweep.yaml: conditions[0].schedule.wobble: line 21: "),
                    HasSubstr("unknown parameter (allowed: amplitude")));
  EXPECT_THAT(ErrorOf(Spec(R"(  - name: a
  - name: b
  - name: c
  - name: d
    stages:
      - {steps: 30000, schedule: {family: constant}}
      - {steps: 120000, schedule: {family: cosine_annealing, T_0: 0}}
)")),
              AllOf(StartsWith("sweep.yaml: conditions[3].stages[1].schedule.T_0: line 27: "),
                    HasSubstr("got 0")));
  EXPECT_THAT(ErrorOf(Spec(R"(  - stages:
      - {steps: 30000, schedule: {family: constant}}
      - {steps: 0, schedule: {family: constant}}
)")),
              StartsWith("sweep.yaml: conditions[0].stages[1].steps: line 23: must be at least 1"));
}

TEST(SweepSpecYamlTest, GridErrorsNameTheKeyOrTheValue) {
  EXPECT_THAT(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal}
    grid: {schedule.amplitude_frac: [0.25, -1]}
)")),
              AllOf(StartsWith("sweep.yaml: conditions[0].grid.schedule.amplitude_frac[1]: line "
                               "22: schedule 'sinusoidal': amplitude_frac"),
                    HasSubstr("got -1")));
  EXPECT_EQ(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal}
    grid: {schedule.period: []}
)")),
            "sweep.yaml: conditions[0].grid.schedule.period: line 22: must list at least one "
            "value: an empty list makes no conditions");
  EXPECT_EQ(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal}
    grid: {schedule.period: 100}
)")),
            "sweep.yaml: conditions[0].grid.schedule.period: line 22: must be a list of values "
            "(one condition each)");
  EXPECT_EQ(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal}
    grid: {schedule.period: [100, 100]}
)")),
            "sweep.yaml: conditions[0].grid.schedule.period[1]: line 22: '100' is listed twice "
            "(also conditions[0].grid.schedule.period[0]): it would make two conditions of one "
            "name");
  EXPECT_THAT(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal}
    grid: {schedule: [{family: constant}], schedule.period: [100]}
)")),
              StartsWith("sweep.yaml: conditions[0].grid.schedule.period: line 22: overlaps grid "
                         "key 'schedule'"));
  EXPECT_THAT(ErrorOf(Spec("  - grid: {observe: [none, live]}\n")),
              StartsWith("sweep.yaml: conditions[0].grid.observe: line 21: a grid varies keys of "
                         "the condition's run config"));
  EXPECT_THAT(ErrorOf(Spec("  - grid: {\"schedule..period\": [1]}\n")),
              StartsWith("sweep.yaml: conditions[0].grid.schedule..period: line 21: "
                         "'schedule..period' is not a key path"));
  EXPECT_EQ(ErrorOf(Spec(R"(  - stages:
      - {steps: 30000, schedule: {family: constant}}
      - {steps: 120000, schedule: {family: constant}}
    grid:
      stages[2].steps: [5]
)")),
            "sweep.yaml: conditions[0].grid.stages[2].steps: line 25: cannot place its values in "
            "the condition: stages has 2 items, so no item 2");
  EXPECT_EQ(ErrorOf(Spec("  - {n_envs: 2, grid: {n_envs.count: [5]}}\n")),
            "sweep.yaml: conditions[0].grid.n_envs.count: line 21: cannot place its values in the "
            "condition: n_envs is a single value, not a mapping with 'count'");
  // A mapping the grid creates is the grid key's.
  EXPECT_EQ(ErrorOf(Spec("  - grid: {n_envs.count: [5]}\n")),
            "sweep.yaml: conditions[0].grid.n_envs.count: must be an integer, got a mapping");
  EXPECT_THAT(ErrorOf(Spec("  - grid: {schedule.period: [5]}\n")),
              StartsWith("sweep.yaml: conditions[0].grid.schedule.period: a schedule needs a "
                         "'family'"));
  EXPECT_EQ(ErrorOf(Spec("  - grid: {}\n")),
            "sweep.yaml: conditions[0].grid: line 21: must map at least one key path to values "
            "(or be left out)");
}

TEST(SweepSpecYamlTest, AnEmptyGridIsRefused) {
  EXPECT_EQ(ErrorOf(absl::StrCat(kBase, "  []\n")),
            "sweep.yaml: conditions: line 21: needs at least one condition: an empty grid makes "
            "no runs");
  EXPECT_THAT(ErrorOf(std::string(kBase)),
              StartsWith("sweep.yaml: conditions: line 21: must be a list of conditions"));
  EXPECT_THAT(ErrorOf(Spec("", "conditions:\n", "")),
              StartsWith("sweep.yaml: conditions: missing"));
}

TEST(SweepSpecYamlTest, DuplicateNamesNameBothConditions) {
  EXPECT_EQ(ErrorOf(Spec("  - name: static\n  - {}\n")),
            "sweep.yaml: conditions[1]: line 22: duplicate condition name 'static' (also "
            "conditions[0].name, line 21): condition names must be unique; give one of them a "
            "name");
  EXPECT_EQ(ErrorOf(Spec(R"(  - schedule: {family: sinusoidal, amplitude_frac: 0.5}
  - name: sinusoidal amplitude_frac=0.5
  - schedule: {family: sinusoidal}
    grid: {schedule.amplitude_frac: [0.25, 0.5]}
  - {schedule: {family: sinusoidal}}
)")),
            "2 problems in sweep.yaml:\n"
            "  sweep.yaml: conditions[2]: line 23: duplicate condition name 'sinusoidal "
            "amplitude_frac=0.5' (also conditions[1].name, line 22): condition names must be "
            "unique; give one of them a name\n"
            "  sweep.yaml: conditions[3]: line 25: duplicate condition name 'sinusoidal' (also "
            "conditions[0], line 21): condition names must be unique; give one of them a name");
}

TEST(SweepSpecYamlTest, AtMostTenThousandRuns) {
  std::vector<int> sizes;
  for (int size = 1; size <= 2501; ++size) sizes.push_back(size);
  const std::string grid = absl::StrCat("  - grid: {pool.size: [", absl::StrJoin(sizes, ", "),
                                        "]}\n");
  EXPECT_EQ(ErrorOf(Spec(grid)),
            "sweep.yaml: conditions: line 21: 5002 trials x 2 seeds would make 10004 runs; a "
            "sweep may make at most 10000");
  sizes.resize(2500);
  const SweepSpec spec = Parse(Spec(absl::StrCat("  - grid: {pool.size: [",
                                                 absl::StrJoin(sizes, ", "), "]}\n")));
  EXPECT_EQ(spec.trials.size() * spec.seeds.size(), 10000u);
  EXPECT_THAT(ErrorOf(Spec("  - name: a\n", "seeds: 2", "seeds: 1000000000000")),
              HasSubstr("2 trials x 1000000000000 seeds would make 2000000000000 runs"));
}

TEST(SweepSpecYamlTest, ReportsEveryProblemTogether) {
  EXPECT_EQ(ErrorOf(Spec(R"(  - name: a
    wobble: 1
  - schedule: {family: sinusoidal}
    grid: {schedule.period: []}
  - name: c
    ppo: {gamma: 2}
)",
                         "seeds: 2", "seeds: 0")),
            "4 problems in sweep.yaml:\n"
            "  sweep.yaml: seeds: line 1: must be at least 1, got 0\n"
            "  sweep.yaml: conditions[0].wobble: line 22: unknown key 'wobble' in conditions[0] "
            "(allowed: name, grid, observe, schedule, stages, env, total_timesteps, n_envs, "
            "context, feature, training_range, pool, evaluation, ppo, coverage)\n"
            "  sweep.yaml: conditions[1].grid.schedule.period: line 24: must list at least one "
            "value: an empty list makes no conditions\n"
            "  sweep.yaml: conditions[2].ppo.gamma: line 26: must be in [0, 1], got 2");
}

TEST(SweepSpecYamlTest, ABaseProblemIsReportedOnceAsARunConfigsWouldBe) {
  const std::string conditions = R"(  - name: a
  - schedule: {family: sinusoidal}
    grid: {schedule.period: [100, 200]}
)";
  EXPECT_EQ(ErrorOf(Spec(conditions, "gamma: 0.99", "gamma: 2")),
            "sweep.yaml: ppo.gamma: line 19: must be in [0, 1], got 2");
  EXPECT_EQ(ErrorOf(Spec(conditions, "freq: 10000", "freq: often")),
            "sweep.yaml: evaluation.freq: line 10: must be an integer, got 'often'");
  // A base problem that a condition's own key hides is not the condition's.
  EXPECT_EQ(ErrorOf(Spec("  - {name: a, ppo: {gamma: 0.9}}\n  - name: b\n", "gamma: 0.99",
                         "gamma: 2")),
            "sweep.yaml: ppo.gamma: line 19: must be in [0, 1], got 2");
  EXPECT_EQ(ErrorOf(Spec("  - {name: a, ppo: {gamma: 0.9}}\n", "gamma: 0.99", "gamma: 2")),
            "OK");
}

TEST(SweepSpecYamlTest, EveryConfigWithConditionsParses) {
  int parsed = 0;
  std::optional<ConfigFile> quickstart_file;
  for (const ConfigFile& config : ConfigFiles()) {
    if (config.kind != ConfigFile::Kind::kSweep) continue;
    absl::StatusOr<SweepSpec> spec = ParseSweepSpecYaml(config.text, config.path.string());
    EXPECT_TRUE(spec.ok()) << spec.status();
    parsed += spec.ok();
    if (config.path.filename() == "quickstart.yaml") quickstart_file = config;
  }
  EXPECT_GE(parsed, 1);

  ASSERT_TRUE(quickstart_file.has_value());
  absl::StatusOr<SweepSpec> quickstart =
      ParseSweepSpecYaml(quickstart_file->text, "quickstart.yaml");
  ASSERT_TRUE(quickstart.ok()) << quickstart.status();
  EXPECT_EQ(quickstart->name, "quickstart");
  EXPECT_THAT(quickstart->seeds, ElementsAre(0, 1, 2));
  EXPECT_THAT(Trials(*quickstart),
              ElementsAre("static | static | none", "static | static | live",
                          "sinusoidal | sinusoidal | none", "sinusoidal | sinusoidal | live",
                          "cosine_annealing | cosine_annealing | none",
                          "cosine_annealing | cosine_annealing | live"));
  EXPECT_EQ(quickstart->baseline, "static");
  const RunSpec cosine = RunOf(quickstart->trials[5]);
  EXPECT_EQ(Param(cosine, 0, "T_0"), 250);
  EXPECT_EQ(Param(cosine, 0, "neighborhood_radius_frac"), 0.2);
  EXPECT_THAT(cosine.pool_values, ElementsAre(0.35, 0.41, 0.48, 0.55, 0.62, 0.68, 0.75));
  EXPECT_EQ(cosine.total_timesteps, 150000);
  EXPECT_EQ(Param(RunOf(quickstart->trials[2]), 0, "amplitude_frac"), 0.25);
}

// The sweep spec of configs/ named `file` (e.g. "cartpole_table.yaml"), parsed; none if absent.
std::optional<SweepSpec> ConfigSweep(const std::string& file) {
  for (const ConfigFile& config : ConfigFiles()) {
    if (config.path.filename() == file) return Parse(config.text);
  }
  return std::nullopt;
}

// The 40-seed table is the paper's table with more seeds: the same trials, the same configs.
TEST(SweepSpecYamlTest, TheFortySeedTableRunsThePapersTrials) {
  const std::optional<SweepSpec> table = ConfigSweep("cartpole_table.yaml");
  const std::optional<SweepSpec> forty = ConfigSweep("cartpole_table_seeds40.yaml");
  ASSERT_TRUE(table.has_value() && forty.has_value());
  EXPECT_EQ(table->seeds.size(), 10u);
  ASSERT_EQ(forty->seeds.size(), 40u);
  EXPECT_EQ(forty->seeds.back(), 39u);
  EXPECT_EQ(forty->baseline, table->baseline);
  ASSERT_EQ(forty->trials.size(), table->trials.size());
  EXPECT_EQ(table->trials.size(), 42u);
  for (size_t i = 0; i < table->trials.size(); ++i) {
    EXPECT_EQ(Trials(*forty)[i], Trials(*table)[i]);
    EXPECT_EQ(forty->trials[i].config, table->trials[i].config) << Trials(*table)[i];
  }
}

// The Walker sweep sized for 2 cores runs some of the paper's Walker table's trials, unchanged.
TEST(SweepSpecYamlTest, TheSmallWalkerSweepRunsTrialsOfThePapersTable) {
  const std::optional<SweepSpec> table = ConfigSweep("bipedal_walker_comx.yaml");
  const std::optional<SweepSpec> best = ConfigSweep("bipedal_walker_comx_best.yaml");
  ASSERT_TRUE(table.has_value() && best.has_value());
  EXPECT_THAT(Trials(*best), ElementsAre("static | static | none", "static | static | live",
                                         "sinusoidal amplitude=0.3 period=300 | sinusoidal | live",
                                         "levy_walk std_frac=0.008 | levy_walk | none"));
  for (const SweepTrial& trial : best->trials) {
    const auto same = std::find_if(table->trials.begin(), table->trials.end(),
                                   [&](const SweepTrial& other) {
                                     return other.condition == trial.condition &&
                                            other.observe == trial.observe;
                                   });
    ASSERT_NE(same, table->trials.end()) << trial.condition;
    EXPECT_EQ(trial.config, same->config) << trial.condition;
  }
}

TEST(SweepSpecYamlTest, TheHeadersExampleParses) {
  const std::string example = HeaderExample("run/sweep_spec_yaml.h");
  ASSERT_THAT(example, HasSubstr("conditions:"));
  const SweepSpec spec = Parse(example);
  EXPECT_THAT(Trials(spec),
              ElementsAre("static | static | none", "static | static | live",
                          "sinusoidal amplitude_frac=0.25 | sinusoidal | none",
                          "sinusoidal amplitude_frac=0.25 | sinusoidal | live",
                          "sinusoidal amplitude_frac=0.5 | sinusoidal | none",
                          "sinusoidal amplitude_frac=0.5 | sinusoidal | live",
                          "curriculum | multi_stage | none", "curriculum | multi_stage | live",
                          "pool15 | static | live"));
}

}  // namespace
}  // namespace dcs::run
