// Copyright 2026 The DCS Authors.
#include "run/run_spec_yaml.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/run/source_files.h"

namespace dcs::run {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using enum actor::Split;

// A valid CartPole config; tests change one thing in it.
constexpr char kBase[] = R"(env: cartpole
seed: 3
total_timesteps: 150000
feature: length
training_range: [0.35, 0.75]
pool: {size: 7}
observe: live
evaluation:
  freq: 10000
  episodes: 30
  contexts:
    id: [0.4, 0.5]
    ood_low: [0.06, 0.12]
    ood_high: [0.92, 1.32]
)";

// kBase with `from` replaced by `to` (which must occur).
std::string Edit(absl::string_view from, absl::string_view to) {
  const std::string text(kBase);
  EXPECT_TRUE(absl::StrContains(text, from)) << from;
  return absl::StrReplaceAll(text, {{from, to}});
}

// The error message of parsing `text`, or "OK".
std::string ErrorOf(const std::string& text) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(text, "run.yaml");
  if (spec.ok()) return "OK";
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  return std::string(spec.status().message());
}

TEST(RunSpecYamlTest, EveryConfigInConfigsParsesAndValidates) {
  int parsed = 0;
  for (const ConfigFile& config : ConfigFiles()) {
    if (config.kind != ConfigFile::Kind::kRun) continue;  // their own tests read the others
    absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(config.text, config.path.string());
    EXPECT_TRUE(spec.ok()) << spec.status();
    if (spec.ok()) {
      EXPECT_TRUE(ValidateRunSpec(*spec).ok()) << config.path;
      ++parsed;
    }
  }
  EXPECT_GE(parsed, 5);
}

TEST(RunSpecYamlTest, TheHeadersExampleParses) {
  const std::string example = HeaderExample("run/run_spec_yaml.h");
  ASSERT_THAT(example, HasSubstr("stages:"));
  // It shows `schedule` and `stages` together, as alternatives: keep the stages.
  const std::string stages_only =
      absl::StrReplaceAll(example, {{"schedule: {family: sinusoidal", "# schedule: {"}});
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(stages_only, "run_spec_yaml.h");
  ASSERT_TRUE(spec.ok()) << spec.status() << "\n" << stages_only;
  EXPECT_EQ(spec->stages.size(), 2u);
  EXPECT_THAT(ErrorOf(example), HasSubstr("not both"));
}

TEST(RunSpecYamlTest, ThePaperConfigsSayWhatTheyShould) {
  const std::filesystem::path dir = std::filesystem::path(DCS_SOURCE_DIR) / "configs";
  auto load = [&](const std::string& name) {
    std::ifstream file(dir / name);
    std::stringstream text;
    text << file.rdbuf();
    absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(text.str(), name);
    EXPECT_TRUE(spec.ok()) << spec.status();
    return spec.value_or(RunSpec());
  };
  const RunSpec observed = load("cartpole_length_pool7_sinusoidal_observed.yaml");
  EXPECT_THAT(observed.pool_values, ElementsAre(0.35, 0.41, 0.48, 0.55, 0.62, 0.68, 0.75));
  ASSERT_EQ(observed.stages.size(), 1u);
  EXPECT_EQ(observed.stages[0].steps, 0);
  EXPECT_EQ(observed.stages[0].schedule.family, "sinusoidal");
  EXPECT_EQ(observed.observe, env::ObserveMode::kLive);
  EXPECT_EQ(observed.eval_values(kId).size() + observed.eval_values(kOodLow).size() +
                observed.eval_values(kOodHigh).size(),
            15u);

  const RunSpec standard = load("cartpole_default_static.yaml");
  EXPECT_EQ(standard.context.at("initial_state_lower"), -0.05);
  EXPECT_EQ(standard.context.at("initial_state_upper"), 0.05);
  EXPECT_THAT(standard.stages, IsEmpty());

  const RunSpec walker = load("bipedal_walker_comx_pool3_static_blind.yaml");
  EXPECT_EQ(walker.feature, "COM_X");
  EXPECT_EQ(walker.pool_size, 3);
  EXPECT_EQ(walker.total_timesteps, 3'000'000);

  const RunSpec car = load("car_racing_comy_pool3_static_blind.yaml");
  EXPECT_EQ(car.feature, "COM_Y");
  EXPECT_EQ(car.eval_freq, 150'000);
  EXPECT_EQ(car.total_timesteps, 1'500'000);
  EXPECT_THAT(car.ppo.context_layers, IsEmpty());  // SB3's CombinedExtractor
}

TEST(RunSpecYamlTest, ReadsEveryField) {
  const std::string text = R"(env: bipedal_walker
seed: 18446744073709551615
total_timesteps: 3e6
n_envs: 4
context: {PAYLOAD_MASS: 2.0, PAYLOAD_RADIUS: 0.5}
feature: COM_X
training_range: [-0.6, 0.6]
pool: {values: [-0.6, 0, 0.6]}
stages:
  - {steps: 30000, schedule: {family: constant}}
  - steps: 120000
    schedule: {family: cosine_annealing, T_0: 250, neighborhood_radius_frac: 0.2}
observe: initial
evaluation:
  freq: 50000
  episodes: 12
  contexts: {id: [0.0], ood_low: [-1.7], ood_high: [1.7]}
ppo: {learning_rate: 1.0e-4, n_steps: 512, batch_size: 32, n_epochs: 4, gamma: 0.999,
      gae_lambda: 0.9, clip_range: 0.1, clip_range_vf: 0.3, normalize_advantage: false,
      ent_coef: 0.01, vf_coef: 0.25, max_grad_norm: 1.0, target_kl: 0.02,
      pi_layers: [128, 64], vf_layers: [32], log_std_init: -0.5, adam_eps: 1.0e-8,
      cnn_features: 128}
)";
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(text, "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->env, "bipedal_walker");
  EXPECT_EQ(spec->seed, 18446744073709551615u);
  EXPECT_EQ(spec->total_timesteps, 3'000'000);
  EXPECT_EQ(spec->n_envs, 4);
  EXPECT_EQ(spec->context.at("PAYLOAD_MASS"), 2.0);
  EXPECT_EQ(spec->feature, "COM_X");
  EXPECT_EQ(spec->range_lo, -0.6);
  EXPECT_EQ(spec->range_hi, 0.6);
  EXPECT_THAT(spec->pool_values, ElementsAre(-0.6, 0, 0.6));
  ASSERT_EQ(spec->stages.size(), 2u);
  EXPECT_EQ(spec->stages[0].steps, 30'000);
  EXPECT_EQ(spec->stages[0].schedule.family, "constant");
  EXPECT_EQ(spec->stages[1].steps, 120'000);
  EXPECT_EQ(spec->stages[1].schedule.family, "cosine_annealing");
  EXPECT_EQ(std::get<double>(spec->stages[1].schedule.params.at("T_0")), 250);
  EXPECT_EQ(spec->observe, env::ObserveMode::kInitial);
  EXPECT_EQ(spec->eval_freq, 50'000);
  EXPECT_EQ(spec->eval_episodes, 12);
  EXPECT_THAT(spec->eval_values(kOodHigh), ElementsAre(1.7));
  const PpoConfig& ppo = spec->ppo;
  EXPECT_EQ(ppo.learning_rate, 1e-4);
  EXPECT_EQ(ppo.n_steps, 512);
  EXPECT_EQ(ppo.batch_size, 32);
  EXPECT_EQ(ppo.n_epochs, 4);
  EXPECT_EQ(ppo.gamma, 0.999);
  EXPECT_EQ(ppo.gae_lambda, 0.9);
  EXPECT_EQ(ppo.clip_range, 0.1);
  EXPECT_EQ(ppo.clip_range_vf, 0.3);
  EXPECT_FALSE(ppo.normalize_advantage);
  EXPECT_EQ(ppo.ent_coef, 0.01);
  EXPECT_EQ(ppo.vf_coef, 0.25);
  EXPECT_EQ(ppo.max_grad_norm, 1.0);
  EXPECT_EQ(ppo.target_kl, 0.02);
  EXPECT_THAT(ppo.pi_layers, ElementsAre(128, 64));
  EXPECT_THAT(ppo.vf_layers, ElementsAre(32));
  EXPECT_EQ(ppo.log_std_init, -0.5);
  EXPECT_EQ(ppo.adam_eps, 1e-8);
  EXPECT_EQ(ppo.cnn_features, 128);
}

TEST(RunSpecYamlTest, AbsentSectionsTakeRunSpecDefaults) {
  const std::string text = R"(evaluation:
  contexts: {id: [0.5]}
)";
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(text, "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  const RunSpec defaults;
  EXPECT_EQ(spec->env, defaults.env);
  EXPECT_EQ(spec->seed, defaults.seed);
  EXPECT_EQ(spec->total_timesteps, defaults.total_timesteps);
  EXPECT_EQ(spec->n_envs, defaults.n_envs);
  EXPECT_THAT(spec->context, IsEmpty());
  EXPECT_EQ(spec->feature, defaults.feature);
  EXPECT_EQ(spec->range_lo, defaults.range_lo);
  EXPECT_EQ(spec->range_hi, defaults.range_hi);
  EXPECT_EQ(spec->pool_size, defaults.pool_size);
  EXPECT_THAT(spec->pool_values, IsEmpty());
  EXPECT_THAT(spec->stages, IsEmpty());  // static
  EXPECT_EQ(spec->observe, defaults.observe);
  EXPECT_EQ(spec->eval_freq, defaults.eval_freq);
  EXPECT_EQ(spec->eval_episodes, defaults.eval_episodes);
  EXPECT_THAT(spec->eval_values(kId), ElementsAre(0.5));
  EXPECT_THAT(spec->eval_values(kOodLow), IsEmpty());
  const PpoConfig ppo;
  EXPECT_EQ(spec->ppo.learning_rate, ppo.learning_rate);
  EXPECT_EQ(spec->ppo.n_steps, ppo.n_steps);
  EXPECT_EQ(spec->ppo.batch_size, ppo.batch_size);
  EXPECT_EQ(spec->ppo.clip_range_vf, std::nullopt);
  EXPECT_EQ(spec->ppo.target_kl, std::nullopt);
  EXPECT_EQ(spec->ppo.pi_layers, ppo.pi_layers);

  // A partial ppo section keeps the other defaults.
  absl::StatusOr<RunSpec> partial =
      ParseRunSpecYaml(absl::StrCat(kBase, "ppo: {gamma: 0.98}\n"), "run.yaml");
  ASSERT_TRUE(partial.ok()) << partial.status();
  EXPECT_EQ(partial->ppo.gamma, 0.98);
  EXPECT_EQ(partial->ppo.learning_rate, ppo.learning_rate);
  EXPECT_EQ(partial->ppo.n_epochs, ppo.n_epochs);
}

TEST(RunSpecYamlTest, NullMeansNoneForClipRangeVfAndTargetKl) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(
      absl::StrCat(kBase, "ppo: {clip_range_vf: null, target_kl: ~}\n"), "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->ppo.clip_range_vf, std::nullopt);
  EXPECT_EQ(spec->ppo.target_kl, std::nullopt);

  spec = ParseRunSpecYaml(absl::StrCat(kBase, "ppo: {clip_range_vf: 0.2, target_kl: 0.01}\n"),
                          "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_EQ(spec->ppo.clip_range_vf, 0.2);
  EXPECT_EQ(spec->ppo.target_kl, 0.01);

  // Null elsewhere is not a number.
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {gamma: null}\n")),
              AllOf(HasSubstr("ppo.gamma"), HasSubstr("must be a number, got null")));
}

TEST(RunSpecYamlTest, OneScheduleIsOneStageForTheWholeRun) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(
      absl::StrCat(kBase, "schedule: {family: sinusoidal, amplitude_frac: 0.25, period: 125}\n"),
      "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  ASSERT_EQ(spec->stages.size(), 1u);
  EXPECT_EQ(spec->stages[0].steps, 0);
  EXPECT_EQ(spec->stages[0].schedule.family, "sinusoidal");
  EXPECT_EQ(std::get<double>(spec->stages[0].schedule.params.at("amplitude_frac")), 0.25);
}

TEST(RunSpecYamlTest, StagesAreReadInOrderWithTheirSteps) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(absl::StrCat(kBase, R"(stages:
  - {steps: 30000, schedule: {family: constant}}
  - {steps: 30000, schedule: {family: sinusoidal, amplitude_frac: 0.5, period: 125}}
  - {steps: 45000, schedule: {family: cosine_annealing, T_0: 250}}
  - {steps: 45000, schedule: {family: identity}}
)"),
                                                  "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  std::vector<std::string> families;
  std::vector<int64_t> steps;
  for (const RunSpec::Stage& stage : spec->stages) {
    families.push_back(stage.schedule.family);
    steps.push_back(stage.steps);
  }
  EXPECT_THAT(families, ElementsAre("constant", "sinusoidal", "cosine_annealing", "identity"));
  EXPECT_THAT(steps, ElementsAre(30'000, 30'000, 45'000, 45'000));
}

TEST(RunSpecYamlTest, UnknownKeysAreNamedWithTheirPathAndTheAllowedKeys) {
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "total_timestep: 5\n")),
              AllOf(HasSubstr("run.yaml"), HasSubstr("unknown key 'total_timestep'"),
                    HasSubstr("top level"), HasSubstr("line 15"), HasSubstr("total_timesteps")));
  EXPECT_THAT(ErrorOf(Edit("  contexts:", "  contxts:")),
              AllOf(HasSubstr("evaluation.contxts"), HasSubstr("unknown key 'contxts'"),
                    HasSubstr("line 11"), HasSubstr("allowed: freq, episodes, contexts")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {learning_rat: 0.001}\n")),
              AllOf(HasSubstr("ppo.learning_rat"), HasSubstr("unknown key 'learning_rat'"),
                    HasSubstr("learning_rate")));
  EXPECT_THAT(ErrorOf(Edit("    ood_low:", "    ood_lo:")),
              AllOf(HasSubstr("evaluation.contexts.ood_lo"), HasSubstr("id, ood_low, ood_high")));
  EXPECT_THAT(ErrorOf(Edit("pool: {size: 7}", "pool: {sise: 7}")), HasSubstr("pool.sise"));
  EXPECT_THAT(
      ErrorOf(absl::StrCat(kBase, "stages:\n  - {steps: 10, schedul: {family: constant}}\n")),
      AllOf(HasSubstr("stages[0].schedul"), HasSubstr("allowed: steps, schedule")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "seed: 4\n")),
              AllOf(HasSubstr("seed"), HasSubstr("given twice")));
}

TEST(RunSpecYamlTest, MalformedYamlGivesTheLine) {
  EXPECT_THAT(ErrorOf("env: cartpole\nseed: 0\nevaluation: {freq: 10\n  contexts: [\n"),
              AllOf(HasSubstr("run.yaml: line "), HasSubstr("column")));
  EXPECT_THAT(ErrorOf("env: cartpole\nseed: 0\n  bad: indentation\n"),
              HasSubstr("run.yaml: line 3"));
  EXPECT_THAT(ErrorOf(""), HasSubstr("must be a mapping"));
  EXPECT_THAT(ErrorOf("- env: cartpole\n"), HasSubstr("must be a mapping"));
}

TEST(RunSpecYamlTest, WrongTypesNameTheField) {
  EXPECT_THAT(ErrorOf(Edit("freq: 10000", "freq: often")),
              AllOf(HasSubstr("evaluation.freq"), HasSubstr("line 9"),
                    HasSubstr("must be an integer"), HasSubstr("often")));
  EXPECT_THAT(ErrorOf(Edit("freq: 10000", "freq: 100.5")),
              AllOf(HasSubstr("evaluation.freq"), HasSubstr("must be an integer")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {learning_rate: fast}\n")),
              AllOf(HasSubstr("ppo.learning_rate"), HasSubstr("must be a number")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {learning_rate: \"0.001\"}\n")),
              AllOf(HasSubstr("ppo.learning_rate"), HasSubstr("the string \"0.001\"")));
  EXPECT_THAT(ErrorOf(Edit("ood_low: [0.06, 0.12]", "ood_low: [0.06, low]")),
              AllOf(HasSubstr("evaluation.contexts.ood_low[1]"), HasSubstr("must be a number")));
  EXPECT_THAT(ErrorOf(Edit("id: [0.4, 0.5]", "id: 0.4")),
              AllOf(HasSubstr("evaluation.contexts.id"), HasSubstr("list of numbers")));
  EXPECT_THAT(ErrorOf(Edit("training_range: [0.35, 0.75]", "training_range: [0.35]")),
              AllOf(HasSubstr("training_range"), HasSubstr("two numbers")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "context: {masspole: heavy}\n")),
              AllOf(HasSubstr("context.masspole"), HasSubstr("must be a number")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {normalize_advantage: maybe}\n")),
              AllOf(HasSubstr("ppo.normalize_advantage"), HasSubstr("true or false")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {pi_layers: [64, 6.5]}\n")),
              HasSubstr("ppo.pi_layers[1]"));
  EXPECT_THAT(ErrorOf(Edit("seed: 3", "seed: -1")),
              AllOf(HasSubstr("seed"), HasSubstr("non-negative integer")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "n_envs: 99999999999\n")),
              AllOf(HasSubstr("n_envs"), HasSubstr("2147483647")));
  EXPECT_THAT(ErrorOf(Edit("env: cartpole", "env: [cartpole]")),
              AllOf(HasSubstr("env"), HasSubstr("must be a name")));
}

TEST(RunSpecYamlTest, RefusesValuesOutOfRangeNamingTheField) {
  EXPECT_THAT(
      ErrorOf(absl::StrCat(kBase, "ppo: {learning_rate: -0.001}\n")),
      AllOf(HasSubstr("ppo.learning_rate"), HasSubstr("line 15"), HasSubstr("must be positive")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {gamma: 1.5}\n")),
              AllOf(HasSubstr("ppo.gamma"), HasSubstr("[0, 1]")));
  EXPECT_THAT(ErrorOf(Edit("ood_high: [0.92, 1.32]", "ood_high: [0.92, 1.32, 6.0]")),
              AllOf(HasSubstr("evaluation.contexts.ood_high[2]"), HasSubstr("line 14"),
                    HasSubstr("[0.05, 5]"), HasSubstr("got 6")));
  EXPECT_THAT(ErrorOf(Edit("env: cartpole", "env: cartpol")),
              AllOf(HasSubstr("env"), HasSubstr("unknown environment 'cartpol'"),
                    HasSubstr("bipedal_walker")));
  EXPECT_THAT(ErrorOf(Edit("feature: length", "feature: lenght")),
              AllOf(HasSubstr("feature: line 4"), HasSubstr("unknown context feature 'lenght'"),
                    HasSubstr("masspole")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "context: {pole_mass: 0.2}\n")),
              AllOf(HasSubstr("context.pole_mass"), HasSubstr("unknown context feature")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "context: {masspole: 2.0}\n")),
              AllOf(HasSubstr("context.masspole"), HasSubstr("[0.01, 1]")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "context: {length: 0.5}\n")),
              AllOf(HasSubstr("context.length"), HasSubstr("varied feature")));
  EXPECT_THAT(
      ErrorOf(absl::StrCat(kBase, "context: {initial_state_lower: 0.1, initial_state_upper: 0}\n")),
      AllOf(HasSubstr("context"), HasSubstr("must not exceed initial_state_upper")));
  EXPECT_THAT(ErrorOf(Edit("pool: {size: 7}", "pool: {values: [0.35, 0.8]}")),
              AllOf(HasSubstr("pool.values[1]"), HasSubstr("within training_range [0.35, 0.75]")));
  EXPECT_THAT(ErrorOf(Edit("pool: {size: 7}", "pool: {size: 0}")),
              AllOf(HasSubstr("pool.size"), HasSubstr("[1, 10000]")));
  EXPECT_THAT(ErrorOf(Edit("pool: {size: 7}", "pool: {size: 3, values: [0.5]}")),
              HasSubstr("exactly one of size and values"));
  EXPECT_THAT(ErrorOf(Edit("training_range: [0.35, 0.75]", "training_range: [0.75, 0.35]")),
              AllOf(HasSubstr("training_range"), HasSubstr("lo < hi")));
  EXPECT_THAT(ErrorOf(Edit("training_range: [0.35, 0.75]", "training_range: [0.01, 0.75]")),
              AllOf(HasSubstr("training_range[0]"), HasSubstr("[0.05, 5]")));
  EXPECT_THAT(ErrorOf(Edit("observe: live", "observe: lve")),
              AllOf(HasSubstr("observe"), HasSubstr("none, initial or live"), HasSubstr("lve")));
  EXPECT_THAT(ErrorOf(Edit("freq: 10000", "freq: 0")),
              AllOf(HasSubstr("evaluation.freq"), HasSubstr("at least 1")));
  EXPECT_THAT(ErrorOf(Edit("episodes: 30", "episodes: 0")),
              AllOf(HasSubstr("evaluation.episodes"), HasSubstr("at least 1")));
  EXPECT_THAT(ErrorOf(Edit("total_timesteps: 150000", "total_timesteps: 0")),
              AllOf(HasSubstr("total_timesteps"), HasSubstr("at least 1")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "n_envs: 0\n")),
              AllOf(HasSubstr("n_envs"), HasSubstr("at least 1")));
  EXPECT_THAT(ErrorOf(R"(evaluation:
  contexts: {id: [], ood_low: []}
)"),
              AllOf(HasSubstr("evaluation.contexts"), HasSubstr("at least one")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "ppo: {context_layers: [64]}\n")),
              AllOf(HasSubstr("ppo.context_layers"), HasSubstr("for image policies"),
                    HasSubstr("cartpole's observation has no image")));
}

TEST(RunSpecYamlTest, AnImagePolicysContextBranchIsReadAndChecked) {
  const std::string car = R"(env: car_racing
feature: COM_Y
training_range: [-0.8, 0.8]
observe: live
evaluation: {freq: 1000, episodes: 1, contexts: {id: [0.0]}}
)";
  absl::StatusOr<RunSpec> spec =
      ParseRunSpecYaml(absl::StrCat(car, "ppo: {context_layers: [64, 16]}\n"), "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  EXPECT_THAT(spec->ppo.context_layers, ElementsAre(64, 16));
  EXPECT_THAT(ErrorOf(absl::StrCat(car, "ppo: {context_layers: [64, 0]}\n")),
              AllOf(HasSubstr("ppo.context_layers"), HasSubstr("positive widths")));
}

TEST(RunSpecYamlTest, CoverageIsOffUnlessAskedForAndNamesTheEnvironmentsProjections) {
  absl::StatusOr<RunSpec> off = ParseRunSpecYaml(kBase, "run.yaml");
  ASSERT_TRUE(off.ok()) << off.status();
  EXPECT_FALSE(off->coverage.has_value());
  absl::StatusOr<RunSpec> defaults = ParseRunSpecYaml(absl::StrCat(kBase, "coverage: {}\n"), "");
  ASSERT_TRUE(defaults.ok()) << defaults.status();
  ASSERT_TRUE(defaults->coverage.has_value());
  EXPECT_EQ(defaults->coverage->window, 50'000);
  EXPECT_TRUE(defaults->coverage->projections.empty());
  absl::StatusOr<RunSpec> named = ParseRunSpecYaml(
      absl::StrCat(kBase, "coverage: {window: 1000, projections: [state]}\n"), "");
  ASSERT_TRUE(named.ok()) << named.status();
  EXPECT_EQ(named->coverage->window, 1000);
  EXPECT_THAT(named->coverage->projections, ElementsAre("state"));

  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "coverage: {window: 0}\n")),
              AllOf(HasSubstr("coverage.window: line 15"), HasSubstr("at least 1, got 0")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "coverage: {projections: [joints]}\n")),
              AllOf(HasSubstr("coverage.projections"),
                    HasSubstr("unknown projection 'joints' (the environment has: state)")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "coverage: {bins: 10}\n")),
              AllOf(HasSubstr("coverage.bins"), HasSubstr("window, projections")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "coverage: {projections: state}\n")),
              HasSubstr("a list of projection names"));
}

TEST(RunSpecYamlTest, ScheduleErrorsNameTheStage) {
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "schedule: {family: sinusodal}\n")),
              AllOf(HasSubstr("schedule: line 15"), HasSubstr("sinusodal")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, R"(stages:
  - {steps: 100, schedule: {family: constant}}
  - {steps: 100, schedule: {family: wobble}}
)")),
              AllOf(HasSubstr("stages[1].schedule"), HasSubstr("line 17"), HasSubstr("wobble")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, R"(stages:
  - {steps: 100, schedule: {family: sinusoidal, amplitude_frac: -1}}
)")),
              AllOf(HasSubstr("stages[0].schedule"), HasSubstr("amplitude_frac")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "stages:\n  - {steps: 100, schedule: {period: 3}}\n")),
              AllOf(HasSubstr("stages[0].schedule"), HasSubstr("family")));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, "stages:\n  - {steps: 100}\n")),
              AllOf(HasSubstr("stages[0]"), HasSubstr("needs a schedule")));
}

TEST(RunSpecYamlTest, StageStepsArePositiveExceptOneWholeRunStage) {
  EXPECT_EQ(ErrorOf(absl::StrCat(kBase, "stages:\n  - {steps: 0, schedule: {family: constant}}\n")),
            "OK");
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, R"(stages:
  - {steps: 100, schedule: {family: constant}}
  - {steps: 0, schedule: {family: constant}}
)")),
              AllOf(HasSubstr("stages[1].steps"), HasSubstr("at least 1")));
  EXPECT_THAT(
      ErrorOf(absl::StrCat(kBase, "stages:\n  - {steps: -5, schedule: {family: constant}}\n")),
      HasSubstr("stages[0].steps"));
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, R"(stages:
  - {steps: 150000, schedule: {family: constant}}
  - {steps: 100, schedule: {family: constant}}
)")),
              AllOf(HasSubstr("stages[1]"), HasSubstr("never run")));
}

TEST(RunSpecYamlTest, ScheduleAndStagesTogetherAreRefused) {
  EXPECT_THAT(ErrorOf(absl::StrCat(kBase, R"(schedule: {family: constant}
stages:
  - {steps: 100, schedule: {family: constant}}
)")),
              AllOf(HasSubstr("stages"), HasSubstr("not both")));
}

TEST(RunSpecYamlTest, ValidateRunSpecNamesFieldsWithoutAText) {
  RunSpec spec;
  EXPECT_THAT(std::string(ValidateRunSpec(spec).message()), HasSubstr("evaluation.contexts"));
  spec.eval_values(kId) = {0.5};
  EXPECT_TRUE(ValidateRunSpec(spec).ok()) << ValidateRunSpec(spec);
  spec.eval_values(kOodHigh) = {0.9, 6.0};
  EXPECT_EQ(
      ValidateRunSpec(spec).message(),
      "evaluation.contexts.ood_high[1]: context feature 'length' must be in [0.05, 5], got 6");
  spec.eval_values(kOodHigh) = {0.9};
  spec.stages.push_back({.steps = 0, .schedule = {.family = "nope"}});
  EXPECT_THAT(std::string(ValidateRunSpec(spec).message()), HasSubstr("stages[0].schedule: "));
  spec.stages[0].schedule.family = "sinusoidal";
  EXPECT_TRUE(ValidateRunSpec(spec).ok()) << ValidateRunSpec(spec);
  spec.ppo.batch_size = 1;
  EXPECT_THAT(std::string(ValidateRunSpec(spec).message()), HasSubstr("ppo.batch_size: "));
}

TEST(RunSpecYamlTest, EvaluationContextsMayLieOutsideTheTrainingRangeButNotThePhysicalBounds) {
  // CarRacing COM_Y: physical bounds [-3, 3], training range [-0.8, 0.8].
  const std::string car = R"(env: car_racing_discrete
feature: COM_Y
training_range: [-0.8, 0.8]
pool: {size: 3}
evaluation: {contexts: {ood_low: [-2.9], ood_high: [2.9]}}
)";
  EXPECT_EQ(ErrorOf(car), "OK");
  EXPECT_THAT(ErrorOf(absl::StrReplaceAll(car, {{"[2.9]", "[3.5]"}})),
              AllOf(HasSubstr("evaluation.contexts.ood_high[0]"), HasSubstr("[-3, 3]")));
}

// The issue's example: every problem named at once, each with its path and line, in a sweep
// spec's format. (amplitude_frac 7 is allowed: a sinusoidal amplitude has no upper bound.)
TEST(RunSpecYamlTest, ListsEveryProblemAtOnce) {
  EXPECT_EQ(ErrorOf(R"(env: cartpole
feature: length
training_range: [0.35, 0.75]
stages:
  - {steps: 0, schedule: {family: sinusoidal, amplitude_frac: 7, period: -3}}
ppo: {learning_rate: -1, gamma: 2}
evaluation: {episodes: 0, contexts: {id: [0.5]}}
)"),
            "4 problems in run.yaml:\n"
            "  run.yaml: evaluation.episodes: line 7: must be at least 1, got 0\n"
            "  run.yaml: stages[0].schedule.period: line 5: schedule 'sinusoidal': period must "
            "be in [1, inf], got -3\n"
            "  run.yaml: ppo.learning_rate: line 6: must be positive, got -1\n"
            "  run.yaml: ppo.gamma: line 6: must be in [0, 1], got 2");
}

// Issue 35's example: a bad learning rate, amplitude and period, each named with its line; the
// amplitude and the period are of one schedule.
TEST(RunSpecYamlTest, ListsEveryBadParameterOfOneSchedule) {
  EXPECT_EQ(ErrorOf(Edit("observe: live", R"(observe: live
schedule: {family: sinusoidal, amplitude_frac: -0.5, period: -3}
ppo:
  learning_rate: -1)")),
            "3 problems in run.yaml:\n"
            "  run.yaml: schedule.amplitude_frac: line 8: schedule 'sinusoidal': amplitude_frac "
            "must be in [0, inf], got -0.5\n"
            "  run.yaml: schedule.period: line 8: schedule 'sinusoidal': period must be in "
            "[1, inf], got -3\n"
            "  run.yaml: ppo.learning_rate: line 10: must be positive, got -1");
}

// A key that cannot be read stops validation, not the reading of the other keys.
TEST(RunSpecYamlTest, ListsEveryKeyThatCannotBeRead) {
  EXPECT_EQ(ErrorOf(Edit("seed: 3", "seed: x\nn_envs: [1]")),
            "2 problems in run.yaml:\n"
            "  run.yaml: seed: line 2: must be a non-negative integer, got 'x'\n"
            "  run.yaml: n_envs: line 3: must be an integer, got a list");
}

// Built in code, the problems come without a file.
TEST(RunSpecYamlTest, ValidateRunSpecListsEveryProblem) {
  absl::StatusOr<RunSpec> spec = ParseRunSpecYaml(kBase, "run.yaml");
  ASSERT_TRUE(spec.ok()) << spec.status();
  spec->n_envs = 0;
  spec->ppo.learning_rate = 0;
  EXPECT_EQ(std::string(ValidateRunSpec(*spec).message()),
            "2 problems:\n  n_envs: must be at least 1, got 0\n"
            "  ppo.learning_rate: must be positive, got 0");
}

}  // namespace
}  // namespace dcs::run
