// Copyright 2026 The DCS Authors.
//
// ParseScheduleSpec: schedule configs as users write them, checked and converted with the
// builder's defaults and fractions of the range (docs/reference.md, "Parameters as fractions of the
// range", env/schedule_config.h).

#include "env/schedule_config.h"

#include <limits>
#include <map>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/string_view.h"
#include "common/status_util.h"
#include "env/schedule_spec.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/env/schedule_test_config.h"

namespace dcs::env {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;


// The parameters of a successfully parsed config, as family P.
template <typename P>
P ParseAs(const ScheduleConfig& config, double min_value, double max_value,
          uint32_t seed = 1) {
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, min_value, max_value, seed);
  EXPECT_TRUE(spec.ok()) << spec.status();
  if (!spec.ok()) return P{};
  EXPECT_EQ(spec->min_value, min_value);
  EXPECT_EQ(spec->max_value, max_value);
  EXPECT_EQ(spec->seed, seed);
  const P* params = std::get_if<P>(&spec->params);
  EXPECT_NE(params, nullptr) << "family " << ScheduleFamilyName(spec->family());
  return params != nullptr ? *params : P{};
}

// The error message of a config that must be refused with INVALID_ARGUMENT.
std::string ErrorOf(const ScheduleConfig& config, double min_value = 0, double max_value = 1) {
  absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, min_value, max_value, 1);
  EXPECT_FALSE(spec.ok()) << "accepted family " << config.family;
  if (spec.ok()) return "";
  EXPECT_EQ(spec.status().code(), absl::StatusCode::kInvalidArgument);
  return std::string(spec.status().message());
}

// ---------------------------------------------------------------------------------------------
// Families

TEST(ScheduleConfigTest, FamilyNamesFollowTheSpecOrder) {
  EXPECT_THAT(ScheduleFamilyNames(),
              ElementsAre("identity", "continuous_incrementer", "sudden_jump", "random_walk",
                          "ornstein_uhlenbeck", "piecewise_constant", "sinusoidal",
                          "cosine_annealing", "sinusoidal_jump", "phased_ou", "levy_walk",
                          "sequential"));
  EXPECT_EQ(ScheduleFamilyName(ScheduleFamily::kOrnsteinUhlenbeck), "ornstein_uhlenbeck");
  EXPECT_EQ(ScheduleFamilyName(ScheduleFamily::kLevyWalk), "levy_walk");
}

TEST(ScheduleConfigTest, EveryFamilyNameParsesToItsFamily) {
  // Minimal valid configs (required parameters only).
  const std::map<std::string, ScheduleConfig> configs = {
      {"continuous_incrementer", Config("continuous_incrementer", {{"delta_frac", 0.01}})},
      {"cosine_annealing", Config("cosine_annealing", {{"T_0", 100.0}})},
      {"piecewise_constant",
       Config("piecewise_constant", {{"values", std::vector<double>{0.2, 0.4}}})},
  };
  for (const std::string& name : ScheduleFamilyNames()) {
    SCOPED_TRACE(name);
    ScheduleConfig config = configs.contains(name) ? configs.at(name) : Config(name);
    if (name == "sequential") config.parts = {Config("identity")};
    absl::StatusOr<ScheduleSpec> spec = ParseScheduleSpec(config, 0, 1, 3);
    ASSERT_TRUE(spec.ok()) << spec.status();
    EXPECT_EQ(ScheduleFamilyName(spec->family()), name);
  }
  // "constant" is Identity (the multi-stage search's name for it).
  absl::StatusOr<ScheduleSpec> constant = ParseScheduleSpec(Config("constant"), 0, 1, 3);
  ASSERT_TRUE(constant.ok()) << constant.status();
  EXPECT_EQ(constant->family(), ScheduleFamily::kIdentity);
}

// The reference (docs/config.md) names every family in order, and of each exactly the
// parameters its reader allows: those an unknown parameter's error lists, both spellings of a
// magnitude included.
TEST(ScheduleConfigTest, TheReferenceListsEveryParameterTheReaderAllows) {
  const std::vector<ScheduleFamilyDoc> reference = ScheduleFamilyReference();
  std::vector<std::string> families;
  for (const ScheduleFamilyDoc& family : reference) families.push_back(family.name);
  EXPECT_EQ(families, ScheduleFamilyNames());
  EXPECT_EQ(reference.front().alias, "constant");

  for (const ScheduleFamilyDoc& family : reference) {
    SCOPED_TRACE(family.name);
    std::set<std::string> described;
    for (const KeyDoc& parameter : family.parameters) {
      for (absl::string_view name : absl::StrSplit(parameter.name, ", ")) {
        described.emplace(name);
      }
    }
    described.erase("parts");  // a sequential schedule's parts are no parameter
    std::set<std::string> allowed;
    for (const absl::Status& problem :
         ScheduleConfigProblems(Config(family.name, {{"no_such_parameter", 1.0}}), 0, 1)) {
      const absl::string_view message = problem.message();
      const size_t start = message.find("(allowed: ");
      if (start == absl::string_view::npos) continue;
      const absl::string_view list =
          message.substr(start + 10, message.rfind(')') - start - 10);
      for (absl::string_view name : absl::StrSplit(list, ", ")) {
        if (name != "none") allowed.emplace(name);
      }
    }
    EXPECT_EQ(described, allowed);
  }
}

// Each parameter's row says what its reader checks: its default and range are those of the
// call that reads it.
TEST(ScheduleConfigTest, TheReferenceGivesEachParametersDefaultAndRange) {
  std::map<std::string, KeyDoc> sinusoidal;
  for (const ScheduleFamilyDoc& family : ScheduleFamilyReference()) {
    if (family.name != "sinusoidal") continue;
    for (const KeyDoc& parameter : family.parameters) sinusoidal[parameter.name] = parameter;
  }
  ASSERT_TRUE(sinusoidal.contains("period"));
  EXPECT_EQ(sinusoidal["period"].default_value, "1");
  EXPECT_EQ(sinusoidal["period"].range, "in [1, inf]");
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"period", 0.0}})),
              HasSubstr(absl::StrCat("period must be ", sinusoidal["period"].range)));
  ASSERT_TRUE(sinusoidal.contains("amplitude, amplitude_frac"));
  EXPECT_EQ(sinusoidal["amplitude, amplitude_frac"].type, "magnitude (of span/2)");
  EXPECT_EQ(sinusoidal["amplitude, amplitude_frac"].default_value, "amplitude_frac 0");
  EXPECT_EQ(sinusoidal["initial_direction"].type, "one of {random, down, up}");
  EXPECT_EQ(sinusoidal["initial_direction"].default_value, "random");
  EXPECT_EQ(ParseAs<SinusoidalParams>(Config("sinusoidal"), 0, 1).initial_direction,
            SinusoidalParams::InitialDirection::kRandom);
}

TEST(ScheduleConfigTest, UnknownFamilyListsTheKnownOnes) {
  const std::string message = ErrorOf(Config("sinus"));
  EXPECT_THAT(message, HasSubstr("sinus"));
  for (const std::string& name : ScheduleFamilyNames()) EXPECT_THAT(message, HasSubstr(name));
  EXPECT_THAT(message, HasSubstr("constant"));
}

// ---------------------------------------------------------------------------------------------
// Unknown, missing, ill-typed and out-of-range parameters

TEST(ScheduleConfigTest, UnknownParameterIsNamedWithTheFamily) {
  const std::string message =
      ErrorOf(Config("sinusoidal", {{"amplitude_frac", 0.2}, {"periode", 100.0}}));
  EXPECT_THAT(message, HasSubstr("sinusoidal"));
  EXPECT_THAT(message, HasSubstr("periode"));
  EXPECT_THAT(message, HasSubstr("allowed"));
  EXPECT_THAT(message, HasSubstr("period"));
  EXPECT_THAT(message, HasSubstr("initial_direction"));

  // Identity takes no parameters.
  EXPECT_THAT(ErrorOf(Config("identity", {{"amplitude", 0.1}})), HasSubstr("amplitude"));
  // Parts belong to sequential only.
  ScheduleConfig with_parts = Config("random_walk");
  with_parts.parts = {Config("identity")};
  EXPECT_THAT(ErrorOf(with_parts), HasSubstr("parts"));
}

// The allowed list of an unknown-parameter error contains every parameter the family accepts,
// both spellings of a magnitude included.
TEST(ScheduleConfigTest, UnknownParameterListsEveryAllowedParameter) {
  const std::string sinusoidal = ErrorOf(Config("sinusoidal", {{"periode", 100.0}}));
  EXPECT_THAT(sinusoidal, HasSubstr("amplitude_frac"));
  EXPECT_THAT(sinusoidal, HasSubstr("amplitude,"));  // the absolute spelling, listed on its own

  const std::string jump = ErrorOf(Config("sudden_jump", {{"step_size", 0.1}}));
  EXPECT_THAT(jump, HasSubstr("step_size_range"));
  EXPECT_THAT(jump, HasSubstr("step_size_frac_range"));
  EXPECT_THAT(jump, HasSubstr("interval_range"));

  const std::string walk = ErrorOf(Config("random_walk", {{"sd", 0.1}}));
  EXPECT_THAT(walk, HasSubstr("std_frac"));
  EXPECT_THAT(walk, HasSubstr("std,"));
}

TEST(ScheduleConfigTest, MissingRequiredParameters) {
  const std::string delta = ErrorOf(Config("continuous_incrementer"));
  EXPECT_THAT(delta, HasSubstr("continuous_incrementer"));
  EXPECT_THAT(delta, HasSubstr("delta"));
  EXPECT_THAT(delta, HasSubstr("missing"));

  const std::string t0 = ErrorOf(Config("cosine_annealing"));  // mode cycle by default
  EXPECT_THAT(t0, HasSubstr("T_0"));
  EXPECT_THAT(t0, HasSubstr("missing"));
  // Mode once needs no T_0.
  EXPECT_TRUE(ParseScheduleSpec(Config("cosine_annealing", {{"mode", std::string("once")}}), 0,
                                1, 1)
                  .ok());

  const std::string values = ErrorOf(Config("piecewise_constant"));
  EXPECT_THAT(values, HasSubstr("values"));
  EXPECT_THAT(values, HasSubstr("missing"));

  const std::string parts = ErrorOf(Config("sequential"));
  EXPECT_THAT(parts, HasSubstr("parts"));
}

TEST(ScheduleConfigTest, IllTypedParameters) {
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"period", std::string("long")}})),
              AllOf(HasSubstr("period"), HasSubstr("number")));
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"initial_direction", 1.0}})),
              AllOf(HasSubstr("initial_direction"), HasSubstr("down"), HasSubstr("up")));
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"initial_direction", std::string("left")}})),
              AllOf(HasSubstr("initial_direction"), HasSubstr("random")));
  EXPECT_THAT(ErrorOf(Config("sudden_jump", {{"interval_range", std::vector<double>{5}}})),
              HasSubstr("interval_range"));
  EXPECT_THAT(ErrorOf(Config("piecewise_constant", {{"values", std::vector<double>{}}})),
              HasSubstr("values"));
  EXPECT_THAT(ErrorOf(Config("ornstein_uhlenbeck", {{"mu", std::string("start")}})),
              AllOf(HasSubstr("mu"), HasSubstr("initial")));
}

// Every parameter is checked whatever the others' checks found, each problem with its field;
// ParseScheduleSpec reports the first.
TEST(ScheduleConfigTest, ProblemsNameEveryBadParameterWithItsField) {
  const ScheduleConfig config =
      Config("sinusoidal", {{"amplitude_frac", -1.0}, {"period", -3.0}, {"periode", 5.0}});
  std::vector<std::string> fields;
  for (const absl::Status& problem : ScheduleConfigProblems(config, 0, 1)) {
    EXPECT_EQ(problem.code(), absl::StatusCode::kInvalidArgument);
    fields.push_back(ErrorField(problem).value_or("?"));
  }
  EXPECT_THAT(fields, ElementsAre("amplitude_frac", "period", "periode"));
  EXPECT_THAT(ErrorOf(config), HasSubstr("amplitude_frac must be in [0, inf], got -1"));
  EXPECT_THAT(ScheduleConfigProblems(Config("sinusoidal", {{"period", 5.0}}), 0, 1), IsEmpty());
  // A period of 0 among other problems: reported with them, at once.
  fields.clear();
  const ScheduleConfig jump = Config(
      "sinusoidal_jump", {{"period", 0.0}, {"interval_range", std::vector<double>{0, 5}}});
  for (const absl::Status& problem : ScheduleConfigProblems(jump, 0, 1)) {
    fields.push_back(ErrorField(problem).value_or("?"));
  }
  EXPECT_THAT(fields, ElementsAre("period", "interval_range"));

  // A sequential schedule's parts, each problem placed in its part.
  ScheduleConfig sequential = Config("sequential");
  sequential.parts = {Config("random_walk", {{"std_frac", -0.1}}), Config("identity"),
                      Config("sinusoidal", {{"period", -1.0}})};
  fields.clear();
  for (const absl::Status& problem : ScheduleConfigProblems(sequential, 0, 1)) {
    fields.push_back(ErrorField(problem).value_or("?"));
  }
  EXPECT_THAT(fields, ElementsAre("parts[0].std_frac", "parts[2].period"));
}

TEST(ScheduleConfigTest, OutOfRangeValuesNameTheAllowedRange) {
  EXPECT_THAT(ErrorOf(Config("sudden_jump", {{"direction_prob", 1.5}})),
              AllOf(HasSubstr("direction_prob"), HasSubstr("[0, 1]"), HasSubstr("1.5")));
  EXPECT_THAT(ErrorOf(Config("ornstein_uhlenbeck", {{"theta", 2.0}})),
              AllOf(HasSubstr("theta"), HasSubstr("[0, 1]")));
  EXPECT_THAT(ErrorOf(Config("random_walk", {{"std_frac", -0.1}})),
              AllOf(HasSubstr("std_frac"), HasSubstr("[0, inf]")));
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 0.0}})),
              AllOf(HasSubstr("T_0"), HasSubstr("[1, ")));
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"period", 0.0}})),
              HasSubstr("period must be in [1, inf], got 0"));
  EXPECT_THAT(ErrorOf(Config("sinusoidal_jump", {{"period", 0.5}})),
              HasSubstr("period must be in [1, inf], got 0.5"));
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 10.5}})),
              AllOf(HasSubstr("T_0"), HasSubstr("whole")));
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 10.0}, {"repel_edge_eps_frac", 0.7}})),
              AllOf(HasSubstr("repel_edge_eps_frac"), HasSubstr("[0, 0.5]")));
  // Values of a piecewise schedule, OU's mu and cosine's start lie within the bounds.
  EXPECT_THAT(ErrorOf(Config("piecewise_constant", {{"values", std::vector<double>{0.5, 1.2}}}),
                      0, 1),
              AllOf(HasSubstr("values"), HasSubstr("[0, 1]"), HasSubstr("1.2")));
  EXPECT_THAT(ErrorOf(Config("ornstein_uhlenbeck", {{"mu", 3.0}}), 0, 2),
              AllOf(HasSubstr("mu"), HasSubstr("[0, 2]")));
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 10.0}, {"start", -0.5}})),
              AllOf(HasSubstr("start"), HasSubstr("[0, 1]")));
  // Intervals: whole steps with 1 <= lo <= hi.
  EXPECT_THAT(ErrorOf(Config("sudden_jump", {{"interval_range", std::vector<double>{0, 5}}})),
              AllOf(HasSubstr("interval_range"), HasSubstr("1 <= lo <= hi")));
  EXPECT_THAT(ErrorOf(Config("sudden_jump", {{"interval_range", std::vector<double>{8, 5}}})),
              HasSubstr("interval_range"));
  EXPECT_THAT(ErrorOf(Config("sudden_jump", {{"interval_range", std::vector<double>{2.5, 5}}})),
              HasSubstr("interval_range"));
  // Magnitude ranges: 0 <= lo <= hi.
  EXPECT_THAT(
      ErrorOf(Config("sudden_jump", {{"step_size_frac_range", std::vector<double>{0.3, 0.1}}})),
      AllOf(HasSubstr("step_size_frac_range"), HasSubstr("0 <= lo <= hi")));
  // end applies to mode once only.
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 10.0}, {"end", 0.5}})),
              HasSubstr("end"));
}

TEST(ScheduleConfigTest, MagnitudeGivenBothAbsolutelyAndAsFractionIsRefused) {
  EXPECT_THAT(ErrorOf(Config("sinusoidal", {{"amplitude", 0.1}, {"amplitude_frac", 0.2}})),
              AllOf(HasSubstr("amplitude"), HasSubstr("amplitude_frac"), HasSubstr("twice")));
  EXPECT_THAT(ErrorOf(Config("continuous_incrementer", {{"delta", 0.1}, {"delta_frac", 0.2}})),
              HasSubstr("twice"));
  EXPECT_THAT(ErrorOf(Config("sudden_jump",
                             {{"step_size_range", std::vector<double>{0.1, 0.2}},
                              {"step_size_frac_range", std::vector<double>{0.1, 0.2}}})),
              HasSubstr("twice"));
  EXPECT_THAT(ErrorOf(Config("ornstein_uhlenbeck", {{"mu", 0.5}, {"mu_frac", 0.5}})),
              HasSubstr("twice"));
}

TEST(ScheduleConfigTest, BadBounds) {
  const ScheduleConfig config = Config("random_walk");
  EXPECT_THAT(ErrorOf(config, 1, 1), HasSubstr("bounds"));
  EXPECT_THAT(ErrorOf(config, 2, 1), HasSubstr("bounds"));
  EXPECT_THAT(ErrorOf(config, 0, std::numeric_limits<double>::infinity()), HasSubstr("bounds"));
  EXPECT_THAT(ErrorOf(config, std::numeric_limits<double>::quiet_NaN(), 1), HasSubstr("bounds"));
}

// ---------------------------------------------------------------------------------------------
// Builder defaults and fractions

TEST(ScheduleConfigTest, SinusoidalAmplitudeIsAFractionOfHalfTheSpan) {
  // Training range [0.35, 0.75] (span 0.4): amplitude_frac 0.25 -> 0.25 * 0.2 = 0.05.
  const auto p = ParseAs<SinusoidalParams>(
      Config("sinusoidal", {{"amplitude_frac", 0.25}, {"period", 125.0}}), 0.35, 0.75);
  EXPECT_NEAR(p.amplitude, 0.05, 1e-15);
  EXPECT_EQ(p.period, 125.0);
  EXPECT_EQ(p.initial_direction, SinusoidalParams::InitialDirection::kRandom);
  // Absolute amplitude is taken as is; defaults: amplitude 0 and period 1 (the builder's 0,
  // which its wave read as one step).
  EXPECT_EQ(ParseAs<SinusoidalParams>(Config("sinusoidal", {{"amplitude", 0.07}}), 0, 4).amplitude,
            0.07);
  const auto d = ParseAs<SinusoidalParams>(Config("sinusoidal"), 0, 4);
  EXPECT_EQ(d.amplitude, 0.0);
  EXPECT_EQ(d.period, 1.0);
}

TEST(ScheduleConfigTest, ContinuousIncrementerDefaults) {
  const auto p = ParseAs<ContinuousIncrementerParams>(
      Config("continuous_incrementer", {{"delta_frac", 0.005}}), 0.35, 0.75);
  EXPECT_NEAR(p.delta, 0.005 * 0.4, 1e-15);
  EXPECT_EQ(p.direction, Direction::kBoth);
  EXPECT_EQ(p.direction_prob, 0.5);
  EXPECT_EQ(p.edge_mode, EdgeMode::kReflect);
  EXPECT_EQ(p.episode_direction, ContinuousIncrementerParams::EpisodeDirection::kRandom);
  EXPECT_EQ(p.noise_std, 0.0);
  ASSERT_TRUE(p.follow_predefined_prob.has_value());
  EXPECT_EQ(*p.follow_predefined_prob, 0.8);
}

TEST(ScheduleConfigTest, CosineAnnealingDefaultsAndRadiusFraction) {
  using P = CosineAnnealingParams;
  const auto p = ParseAs<P>(
      Config("cosine_annealing", {{"T_0", 250.0}, {"neighborhood_radius_frac", 0.2}}), 0.35,
      0.75);
  EXPECT_EQ(p.mode, P::Mode::kCycle);
  EXPECT_EQ(p.t_0, 250);
  EXPECT_EQ(p.t_mult, 1);
  ASSERT_TRUE(p.neighborhood_radius.has_value());
  EXPECT_NEAR(*p.neighborhood_radius, 0.5 * 0.2 * 0.4, 1e-15);  // of span/2
  EXPECT_EQ(p.direction, P::EndDirection::kAuto);
  EXPECT_EQ(p.retarget, P::Retarget::kRestart);
  EXPECT_EQ(p.min_delta, 0.0);
  EXPECT_EQ(p.repel_edge_eps_frac, 0.05);
  EXPECT_FALSE(p.start.has_value());
  EXPECT_FALSE(p.end.has_value());
  // Without a radius (or a zero fraction) the band is the whole range.
  EXPECT_FALSE(ParseAs<P>(Config("cosine_annealing", {{"T_0", 250.0}}), 0, 1)
                   .neighborhood_radius.has_value());
  EXPECT_FALSE(ParseAs<P>(Config("cosine_annealing",
                                 {{"T_0", 250.0}, {"neighborhood_radius_frac", 0.0}}),
                          0, 1)
                   .neighborhood_radius.has_value());
}

TEST(ScheduleConfigTest, RandomWalkStdDefaultIsOnePercentOfTheSpan) {
  EXPECT_NEAR(ParseAs<RandomWalkParams>(Config("random_walk"), -0.6, 0.6).std, 0.012, 1e-15);
  EXPECT_NEAR(ParseAs<RandomWalkParams>(Config("random_walk", {{"std_frac", 0.1}}), 0, 4).std,
              0.4, 1e-15);
  EXPECT_EQ(ParseAs<RandomWalkParams>(Config("random_walk", {{"std", 0.3}}), 0, 4).std, 0.3);
}

TEST(ScheduleConfigTest, SuddenJumpDefaults) {
  const auto p = ParseAs<SuddenJumpParams>(Config("sudden_jump"), 0, 2);
  EXPECT_NEAR(p.step_size.lo, 0.2, 1e-15);  // (0.1, 0.3) * span 2
  EXPECT_NEAR(p.step_size.hi, 0.6, 1e-15);
  EXPECT_EQ(p.interval.lo, 10);
  EXPECT_EQ(p.interval.hi, 30);
  EXPECT_EQ(p.direction, Direction::kBoth);
  EXPECT_EQ(p.direction_prob, 0.5);
  EXPECT_EQ(p.edge_mode, EdgeMode::kClip);
  // An absolute range is taken as is.
  const auto a = ParseAs<SuddenJumpParams>(
      Config("sudden_jump", {{"step_size_range", std::vector<double>{0.05, 0.07}}}), 0, 2);
  EXPECT_EQ(a.step_size.lo, 0.05);
  EXPECT_EQ(a.step_size.hi, 0.07);
}

TEST(ScheduleConfigTest, OrnsteinUhlenbeckDefaultsAndMu) {
  const auto p = ParseAs<OrnsteinUhlenbeckParams>(Config("ornstein_uhlenbeck"), 2, 6);
  EXPECT_EQ(p.theta, 0.05);
  EXPECT_NEAR(p.sigma, 0.08 * 4, 1e-15);
  EXPECT_EQ(p.mu, 4.0);  // the midpoint
  EXPECT_FALSE(p.mu_is_episode_initial);
  EXPECT_EQ(
      ParseAs<OrnsteinUhlenbeckParams>(Config("ornstein_uhlenbeck", {{"mu_frac", 0.25}}), 2, 6).mu,
      3.0);
  EXPECT_EQ(ParseAs<OrnsteinUhlenbeckParams>(Config("ornstein_uhlenbeck", {{"mu", 5.0}}), 2, 6).mu,
            5.0);
  EXPECT_TRUE(ParseAs<OrnsteinUhlenbeckParams>(
                  Config("ornstein_uhlenbeck", {{"mu", std::string("initial")}}), 2, 6)
                  .mu_is_episode_initial);
}

TEST(ScheduleConfigTest, PiecewiseSinusoidalJumpPhasedOuAndLevyDefaults) {
  const auto pc = ParseAs<PiecewiseConstantParams>(
      Config("piecewise_constant", {{"values", std::vector<double>{-0.6, 0.0, 0.6}}}), -0.6, 0.6);
  EXPECT_THAT(pc.values, ElementsAre(-0.6, 0.0, 0.6));
  EXPECT_EQ(pc.interval.lo, 30);
  EXPECT_EQ(pc.interval.hi, 50);

  const auto sj = ParseAs<SinusoidalJumpParams>(Config("sinusoidal_jump"), 0, 2);
  EXPECT_NEAR(sj.amplitude, 0.3 * 2 * 0.5, 1e-15);
  EXPECT_EQ(sj.period, 100.0);
  EXPECT_NEAR(sj.step_size.lo, 0.4, 1e-15);
  EXPECT_NEAR(sj.step_size.hi, 0.8, 1e-15);
  EXPECT_EQ(sj.interval.lo, 80);
  EXPECT_EQ(sj.interval.hi, 150);

  const auto po = ParseAs<PhasedOuParams>(Config("phased_ou"), 1, 3);
  EXPECT_EQ(po.theta, 0.05);
  EXPECT_NEAR(po.sigma, 0.04 * 2, 1e-15);
  EXPECT_THAT(po.values, ElementsAre(1.0, 2.0, 3.0));
  EXPECT_EQ(po.interval.lo, 100);
  EXPECT_EQ(po.interval.hi, 150);

  const auto lw = ParseAs<LevyWalkParams>(Config("levy_walk"), 0, 2);
  EXPECT_NEAR(lw.std, 0.008 * 2, 1e-15);
  EXPECT_NEAR(lw.step_size.lo, 0.4, 1e-15);
  EXPECT_NEAR(lw.step_size.hi, 0.8, 1e-15);
  EXPECT_EQ(lw.interval.lo, 40);
  EXPECT_EQ(lw.interval.hi, 80);
}

// ---------------------------------------------------------------------------------------------
// Sequential

TEST(ScheduleConfigTest, SequentialPartsGetDistinctSeedsAndTheSameBounds) {
  ScheduleConfig config = Config("sequential");
  config.parts = {Config("random_walk"), Config("random_walk"), Config("sudden_jump")};
  const auto p = ParseAs<SequentialParams>(config, 0.35, 0.75, 42);
  ASSERT_EQ(p.parts.size(), 3u);
  EXPECT_NE(p.parts[0].seed, p.parts[1].seed);
  EXPECT_NE(p.parts[1].seed, p.parts[2].seed);
  EXPECT_NE(p.parts[0].seed, p.parts[2].seed);
  for (const ScheduleSpec& part : p.parts) {
    EXPECT_NE(part.seed, 42u);
    EXPECT_EQ(part.min_value, 0.35);
    EXPECT_EQ(part.max_value, 0.75);
  }
  EXPECT_EQ(p.parts[2].family(), ScheduleFamily::kSuddenJump);
  // Deterministic: the same seed gives the same part seeds; another seed, others.
  const auto again = ParseAs<SequentialParams>(config, 0.35, 0.75, 42);
  const auto other = ParseAs<SequentialParams>(config, 0.35, 0.75, 43);
  EXPECT_EQ(again.parts[0].seed, p.parts[0].seed);
  EXPECT_NE(other.parts[0].seed, p.parts[0].seed);
}

TEST(ScheduleConfigTest, SequentialPartSeedsAreNumpySpawnedSeeds) {
  // Part i's base seed is numpy's SeedSequence(seed).spawn(n)[i].generate_state(1)[0], as the
  // reference's make_levy_walk derives its parts' seeds. Expected words printed by
  // numpy 1.24.2 (Debian 12's python3-numpy):
  //   [int(c.generate_state(1)[0]) for c in numpy.random.SeedSequence(42).spawn(3)]
  ScheduleConfig config = Config("sequential");
  config.parts = {Config("identity"), Config("identity"), Config("identity")};
  const auto p42 = ParseAs<SequentialParams>(config, 0, 1, 42);
  ASSERT_EQ(p42.parts.size(), 3u);
  EXPECT_EQ(p42.parts[0].seed, 2684470948u);
  EXPECT_EQ(p42.parts[1].seed, 4091952314u);
  EXPECT_EQ(p42.parts[2].seed, 233227757u);
  const auto p0 = ParseAs<SequentialParams>(config, 0, 1, 0);
  EXPECT_EQ(p0.parts[0].seed, 3757552657u);
  EXPECT_EQ(p0.parts[1].seed, 673228719u);
  EXPECT_EQ(p0.parts[2].seed, 3241444873u);
  const auto p_max = ParseAs<SequentialParams>(config, 0, 1, 4294967295u);
  EXPECT_EQ(p_max.parts[0].seed, 973442627u);
  EXPECT_EQ(p_max.parts[2].seed, 3042058737u);
}

TEST(ScheduleConfigTest, SequentialPropagatesAPartsError) {
  ScheduleConfig config = Config("sequential");
  config.parts = {Config("random_walk"), Config("continuous_incrementer")};
  EXPECT_THAT(ErrorOf(config), AllOf(HasSubstr("continuous_incrementer"), HasSubstr("delta")));
  ScheduleConfig with_params = Config("sequential", {{"std", 0.1}});
  with_params.parts = {Config("random_walk")};
  EXPECT_THAT(ErrorOf(with_params), HasSubstr("std"));
}

TEST(ScheduleConfigTest, ParsedValuesAreNotConfusedWithOtherParameters) {
  // A valid config is not refused because of a parameter the family does read.
  const ScheduleConfig full = Config(
      "cosine_annealing", {{"T_0", 100.0},
                           {"T_mult", 2.0},
                           {"T_max", 500.0},
                           {"mode", std::string("cycle")},
                           {"start", 0.5},
                           {"neighborhood_radius", 0.1},
                           {"min_delta", 0.05},
                           {"direction", std::string("to_min")},
                           {"retarget", std::string("swap")},
                           {"repel_edge_eps_frac", 0.1}});
  const auto p = ParseAs<CosineAnnealingParams>(full, 0, 1);
  EXPECT_EQ(p.t_mult, 2);
  EXPECT_EQ(p.t_max, 500);
  EXPECT_EQ(*p.start, 0.5);
  EXPECT_EQ(*p.neighborhood_radius, 0.1);
  EXPECT_EQ(p.min_delta, 0.05);
  EXPECT_EQ(p.direction, CosineAnnealingParams::EndDirection::kToMin);
  EXPECT_EQ(p.retarget, CosineAnnealingParams::Retarget::kSwap);
  EXPECT_EQ(p.repel_edge_eps_frac, 0.1);
  EXPECT_THAT(ErrorOf(Config("cosine_annealing", {{"T_0", 100.0}, {"T0", 5.0}})),
              AllOf(HasSubstr("T0"), Not(HasSubstr("T_0 missing"))));
}

}  // namespace
}  // namespace dcs::env
