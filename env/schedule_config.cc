// Copyright 2026 The DCS Authors.
#include "env/schedule_config.h"

#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <variant>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "env/schedule_internal.h"

namespace dcs::env {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string FormatBound(double value) {
  return std::isinf(value) ? (value > 0 ? "inf" : "-inf") : absl::StrCat(value);
}

// Reads one schedule config's parameters, remembering which it has read, so that Finish() can
// name any it did not recognise, and keeping every problem found (Check), so that each
// parameter is checked whatever the others' checks found. Every error names the family and the
// parameter, and carries the parameter as its field (common/status_util.h).
class ParamReader {
 public:
  ParamReader(const ScheduleConfig& config, double min_value, double max_value, uint32_t seed)
      : config_(config), min_(min_value), max_(max_value), seed_(seed) {}

  const ScheduleConfig& config() const { return config_; }
  double min() const { return min_; }
  double max() const { return max_; }
  uint32_t seed() const { return seed_; }
  double span() const { return max_ - min_; }
  double midpoint() const { return 0.5 * (min_ + max_); }

  // A number in [lo, hi], `fallback` if absent (nullopt: required).
  absl::Status Number(const std::string& name, std::optional<double> fallback, double lo,
                      double hi, double* out) {
    const ScheduleParam* param = Take(name);
    if (param == nullptr) return Fallback(name, fallback, out);
    const double* value = std::get_if<double>(param);
    if (value == nullptr) return Error(name, "must be a number");
    return InRange(name, *value, lo, hi, out);
  }

  // A non-negative magnitude, given as `name` (absolute) or `fraction_name` (times
  // `scale` * span); `fallback_fraction` if neither (nullopt: required).
  absl::Status Magnitude(const std::string& name, const std::string& fraction_name, double scale,
                         std::optional<double> fallback_fraction, double* out) {
    Allow(name, fraction_name);
    const bool absolute = Has(name);
    const bool fraction = Has(fraction_name);
    if (absolute && fraction) return BothGiven(name, fraction_name);
    if (absolute) return Number(name, std::nullopt, 0, kInf, out);
    double f = 0;
    if (!fraction && !fallback_fraction.has_value()) {
      return Error(name, absl::StrCat("missing (give ", name, " or ", fraction_name, ")"));
    }
    DCS_RETURN_IF_ERROR(Number(fraction_name, fallback_fraction, 0, kInf, &f));
    *out = f * scale * span();
    return absl::OkStatus();
  }

  // A range [lo, hi] of non-negative magnitudes, absolute or as fractions of the span.
  absl::Status MagnitudeRange(const std::string& name, const std::string& fraction_name,
                              Range fallback_fraction, Range* out) {
    Allow(name, fraction_name);
    const bool absolute = Has(name);
    if (absolute && Has(fraction_name)) return BothGiven(name, fraction_name);
    Range range = fallback_fraction;
    const double scale = absolute ? 1.0 : span();
    const std::string& used = absolute ? name : fraction_name;
    if (absolute || Has(fraction_name)) DCS_RETURN_IF_ERROR(Pair(used, &range.lo, &range.hi));
    if (range.lo < 0 || range.lo > range.hi) {
      return Error(used, absl::StrCat("must be [lo, hi] with 0 <= lo <= hi, got [", range.lo,
                                      ", ", range.hi, "]"));
    }
    *out = {range.lo * scale, range.hi * scale};
    return absl::OkStatus();
  }

  // An interval U{lo..hi} in steps: whole numbers with 1 <= lo <= hi.
  absl::Status Interval(const std::string& name, StepRange fallback, StepRange* out) {
    Allow(name);
    *out = fallback;
    if (!Has(name)) return absl::OkStatus();
    double lo = 0;
    double hi = 0;
    DCS_RETURN_IF_ERROR(Pair(name, &lo, &hi));
    if (lo != std::floor(lo) || hi != std::floor(hi) || lo < 1 || lo > hi || hi > 1e12) {
      return Error(name, absl::StrCat("must be [lo, hi] in whole steps with 1 <= lo <= hi, got [",
                                      lo, ", ", hi, "]"));
    }
    *out = {static_cast<int64_t>(lo), static_cast<int64_t>(hi)};
    return absl::OkStatus();
  }

  // A whole number >= `lo`.
  absl::Status Steps(const std::string& name, std::optional<int64_t> fallback, int64_t lo,
                     int64_t* out) {
    double value = 0;
    DCS_RETURN_IF_ERROR(Number(
        name, fallback.has_value() ? std::optional<double>(*fallback) : std::nullopt,
        static_cast<double>(lo), 1e12, &value));
    if (value != std::floor(value)) {
      return Error(name, absl::StrCat("must be a whole number of steps, got ", value));
    }
    *out = static_cast<int64_t>(value);
    return absl::OkStatus();
  }

  // One of `choices`, by name; `fallback` if absent.
  template <typename T>
  absl::Status Choice(const std::string& name, T fallback,
                      const std::vector<std::pair<std::string, T>>& choices, T* out) {
    const ScheduleParam* param = Take(name);
    *out = fallback;
    if (param == nullptr) return absl::OkStatus();
    const std::string* word = std::get_if<std::string>(param);
    std::vector<std::string> names;
    for (const auto& [choice_name, value] : choices) {
      if (word != nullptr && *word == choice_name) {
        *out = value;
        return absl::OkStatus();
      }
      names.push_back(choice_name);
    }
    return Error(name, absl::StrCat("must be one of ", absl::StrJoin(names, ", ")));
  }

  // A non-empty list of values within the schedule's bounds; `fallback` if absent.
  absl::Status Values(const std::string& name, std::optional<std::vector<double>> fallback,
                      std::vector<double>* out) {
    const ScheduleParam* param = Take(name);
    if (param == nullptr) {
      if (!fallback.has_value()) return Error(name, "missing (a list of values)");
      *out = *fallback;
      return absl::OkStatus();
    }
    const auto* values = std::get_if<std::vector<double>>(param);
    if (values == nullptr || values->empty()) return Error(name, "must be a non-empty list");
    for (double value : *values) {
      double checked = 0;
      DCS_RETURN_IF_ERROR(InRange(name, value, min_, max_, &checked));
    }
    *out = *values;
    return absl::OkStatus();
  }

  // An optional value within the schedule's bounds.
  absl::Status OptionalValue(const std::string& name, std::optional<double>* out) {
    Allow(name);
    if (!Has(name)) return absl::OkStatus();
    double value = 0;
    DCS_RETURN_IF_ERROR(Number(name, std::nullopt, min_, max_, &value));
    *out = value;
    return absl::OkStatus();
  }

  bool Has(const std::string& name) const { return config_.params.contains(name); }

  // Counts `names` as parameters of the family, given or not (for Finish()'s list).
  template <typename... Names>
  void Allow(const Names&... names) {
    (known_.insert(std::string(names)), ...);
  }

  // Marks `name` as known; the parameter, or nullptr if absent.
  const ScheduleParam* Take(const std::string& name) {
    known_.insert(name);
    auto it = config_.params.find(name);
    return it == config_.params.end() ? nullptr : &it->second;
  }

  // Keeps `status` as a problem of the config unless it is OK; the caller goes on.
  void Check(absl::Status status) {
    if (!status.ok()) problems_.push_back(std::move(status));
  }

  // Keeps a problem for each parameter no reader asked for, and for parts outside a sequential
  // schedule; then returns every problem kept, in the order found.
  std::vector<absl::Status> Finish() && {
    for (const auto& [name, value] : config_.params) {
      if (!known_.contains(name)) {
        Check(Error(name, absl::StrCat("unknown parameter (allowed: ",
                                       known_.empty() ? "none" : absl::StrJoin(known_, ", "),
                                       ")")));
      }
    }
    if (!config_.parts.empty() && config_.family != "sequential") {
      Check(Error("parts", "only a sequential schedule has parts"));
    }
    return std::move(problems_);
  }

  absl::Status Error(absl::string_view name, absl::string_view message) const {
    return ErrorInField(absl::InvalidArgumentError(absl::StrCat("schedule '", config_.family,
                                                                "': ", name, " ", message)),
                        name);
  }

 private:
  absl::Status Fallback(const std::string& name, std::optional<double> fallback, double* out) {
    if (!fallback.has_value()) return Error(name, "missing");
    *out = *fallback;
    return absl::OkStatus();
  }

  absl::Status InRange(const std::string& name, double value, double lo, double hi,
                       double* out) const {
    if (!std::isfinite(value) || value < lo || value > hi) {
      return Error(name, absl::StrCat("must be in [", FormatBound(lo), ", ", FormatBound(hi),
                                      "], got ", value));
    }
    *out = value;
    return absl::OkStatus();
  }

  absl::Status Pair(const std::string& name, double* lo, double* hi) {
    const ScheduleParam* param = Take(name);
    const auto* values = param == nullptr ? nullptr : std::get_if<std::vector<double>>(param);
    if (values == nullptr || values->size() != 2 || !std::isfinite((*values)[0]) ||
        !std::isfinite((*values)[1])) {
      return Error(name, "must be a list of two numbers [lo, hi]");
    }
    *lo = (*values)[0];
    *hi = (*values)[1];
    return absl::OkStatus();
  }

  absl::Status BothGiven(const std::string& name, const std::string& fraction_name) const {
    return Error(name, absl::StrCat("is given twice: as ", name, " and as ", fraction_name));
  }

  const ScheduleConfig& config_;
  const double min_;
  const double max_;
  const uint32_t seed_;
  std::set<std::string> known_;
  std::vector<absl::Status> problems_;
};

const std::vector<std::pair<std::string, Direction>> kDirections = {
    {"positive", Direction::kPositive}, {"negative", Direction::kNegative},
    {"both", Direction::kBoth}};
const std::vector<std::pair<std::string, EdgeMode>> kEdgeModes = {{"clip", EdgeMode::kClip},
                                                                  {"reflect", EdgeMode::kReflect}};

absl::StatusOr<ScheduleParams> ParseSinusoidal(ParamReader& r) {
  SinusoidalParams p;
  using D = SinusoidalParams::InitialDirection;
  r.Check(r.Magnitude("amplitude", "amplitude_frac", 0.5, 0.0, &p.amplitude));
  // The default was 0, which the wave reads as 1 (a period of one step): the same schedule.
  r.Check(r.Number("period", 1.0, 1, kInf, &p.period));
  r.Check(r.Choice("initial_direction", D::kRandom,
                   {{"random", D::kRandom}, {"down", D::kDown}, {"up", D::kUp}},
                   &p.initial_direction));
  return p;
}

absl::StatusOr<ScheduleParams> ParseCosineAnnealing(ParamReader& r) {
  using P = CosineAnnealingParams;
  P p;
  r.Check(r.Choice("mode", P::Mode::kCycle,
                   {{"cycle", P::Mode::kCycle}, {"once", P::Mode::kOnce}}, &p.mode));
  r.Check(r.Steps("T_0", p.mode == P::Mode::kOnce ? std::optional<int64_t>(200)
                                                    : std::nullopt,
                  1, &p.t_0));
  r.Check(r.Steps("T_mult", 1, 1, &p.t_mult));
  r.Check(r.Steps("T_max", 1000, 1, &p.t_max));
  r.Check(r.OptionalValue("start", &p.start));
  r.Check(r.OptionalValue("end", &p.end));
  if (p.end.has_value() && p.mode != P::Mode::kOnce) {
    return r.Error("end", "applies to mode once only (cycles choose their end by direction)");
  }
  double radius = 0;
  r.Check(r.Magnitude("neighborhood_radius", "neighborhood_radius_frac", 0.5, 0.0,
                      &radius));
  if (radius > 0) p.neighborhood_radius = radius;
  r.Check(r.Number("min_delta", 0.0, 0, kInf, &p.min_delta));
  r.Check(r.Choice("direction", P::EndDirection::kAuto,
                   {{"auto", P::EndDirection::kAuto},
                    {"to_min", P::EndDirection::kToMin},
                    {"to_max", P::EndDirection::kToMax},
                    {"random", P::EndDirection::kRandom}},
                   &p.direction));
  r.Check(r.Choice("retarget", P::Retarget::kRestart,
                   {{"swap", P::Retarget::kSwap},
                    {"restart", P::Retarget::kRestart},
                    {"random", P::Retarget::kRandom}},
                   &p.retarget));
  r.Check(r.Number("repel_edge_eps_frac", 0.05, 0, 0.5, &p.repel_edge_eps_frac));
  return p;
}

absl::StatusOr<ScheduleParams> ParseContinuousIncrementer(ParamReader& r) {
  using P = ContinuousIncrementerParams;
  P p;
  r.Check(r.Magnitude("delta", "delta_frac", 1.0, std::nullopt, &p.delta));
  r.Check(r.Choice("direction", Direction::kBoth, kDirections, &p.direction));
  r.Check(r.Number("direction_prob", 0.5, 0, 1, &p.direction_prob));
  r.Check(r.Choice("edge_mode", EdgeMode::kReflect, kEdgeModes, &p.edge_mode));
  r.Check(r.Choice("episode_direction", P::EpisodeDirection::kRandom,
                   {{"none", P::EpisodeDirection::kNone},
                    {"up", P::EpisodeDirection::kUp},
                    {"down", P::EpisodeDirection::kDown},
                    {"random", P::EpisodeDirection::kRandom}},
                   &p.episode_direction));
  r.Check(r.Number("noise_std", 0.0, 0, kInf, &p.noise_std));
  double follow = 0;
  r.Check(r.Number("follow_predefined_prob", 0.8, 0, 1, &follow));
  p.follow_predefined_prob = follow;
  return p;
}

absl::StatusOr<ScheduleParams> ParseRandomWalk(ParamReader& r) {
  RandomWalkParams p;
  r.Check(r.Magnitude("std", "std_frac", 1.0, 0.01, &p.std));
  return p;
}

absl::StatusOr<ScheduleParams> ParsePiecewiseConstant(ParamReader& r) {
  PiecewiseConstantParams p;
  r.Check(r.Values("values", std::nullopt, &p.values));
  r.Check(r.Interval("interval_range", {30, 50}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParseSuddenJump(ParamReader& r) {
  SuddenJumpParams p;
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range", {0.1, 0.3}, &p.step_size));
  r.Check(r.Interval("interval_range", {10, 30}, &p.interval));
  r.Check(r.Choice("direction", Direction::kBoth, kDirections, &p.direction));
  r.Check(r.Number("direction_prob", 0.5, 0, 1, &p.direction_prob));
  r.Check(r.Choice("edge_mode", EdgeMode::kClip, kEdgeModes, &p.edge_mode));
  return p;
}

absl::StatusOr<ScheduleParams> ParseOrnsteinUhlenbeck(ParamReader& r) {
  const double min_value = r.min();
  OrnsteinUhlenbeckParams p;
  r.Check(r.Number("theta", 0.05, 0, 1, &p.theta));
  r.Check(r.Magnitude("sigma", "sigma_frac", 1.0, 0.08, &p.sigma));
  r.Allow("mu", "mu_frac");
  const ScheduleParam* mu = r.Take("mu");
  if (mu != nullptr && r.Has("mu_frac")) {
    return r.Error("mu", "is given twice: as mu and as mu_frac");
  }
  if (const std::string* word = mu == nullptr ? nullptr : std::get_if<std::string>(mu)) {
    if (*word != "initial") return r.Error("mu", "must be a number or 'initial'");
    p.mu_is_episode_initial = true;  // the paper's variant
  } else if (mu != nullptr) {
    r.Check(r.Number("mu", std::nullopt, min_value, min_value + r.span(), &p.mu));
  } else {
    double fraction = 0.5;
    r.Check(r.Number("mu_frac", 0.5, 0, 1, &fraction));
    p.mu = min_value + fraction * r.span();
  }
  return p;
}

absl::StatusOr<ScheduleParams> ParseSinusoidalJump(ParamReader& r) {
  SinusoidalJumpParams p;
  r.Check(r.Magnitude("amplitude", "amplitude_frac", 0.5, 0.3, &p.amplitude));
  r.Check(r.Number("period", 100.0, 1, kInf, &p.period));
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range", {0.2, 0.4}, &p.step_size));
  r.Check(r.Interval("interval_range", {80, 150}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParsePhasedOu(ParamReader& r) {
  const double min_value = r.min();
  PhasedOuParams p;
  r.Check(r.Number("theta", 0.05, 0, 1, &p.theta));
  r.Check(r.Magnitude("sigma", "sigma_frac", 1.0, 0.04, &p.sigma));
  r.Check(r.Values(
      "values", std::vector<double>{min_value, r.midpoint(), min_value + r.span()}, &p.values));
  r.Check(r.Interval("interval_range", {100, 150}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParseLevyWalk(ParamReader& r) {
  LevyWalkParams p;
  r.Check(r.Magnitude("std", "std_frac", 1.0, 0.008, &p.std));
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range", {0.2, 0.4}, &p.step_size));
  r.Check(r.Interval("interval_range", {40, 80}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParseIdentity(ParamReader&) { return IdentityParams{}; }

// The spec of `config` and every problem found in it (the spec only if there were none).
struct CheckedSchedule {
  std::optional<ScheduleSpec> spec;
  std::vector<absl::Status> problems;
};
CheckedSchedule CheckSchedule(const ScheduleConfig& config, double min_value, double max_value,
                              uint32_t seed);

absl::StatusOr<ScheduleParams> ParseSequential(ParamReader& r) {
  const std::vector<ScheduleConfig>& parts = r.config().parts;
  if (parts.empty()) return r.Error("parts", "missing (a list of schedules)");
  SequentialParams sequential;
  for (size_t i = 0; i < parts.size(); ++i) {
    CheckedSchedule part = CheckSchedule(
        parts[i], r.min(), r.max(), internal::SpawnSeed(r.seed(), static_cast<uint32_t>(i)));
    for (absl::Status& problem : part.problems) {
      r.Check(ErrorInField(std::move(problem), absl::StrCat("parts[", i, "]")));
    }
    if (part.spec.has_value()) sequential.parts.push_back(*std::move(part.spec));
  }
  return sequential;
}

// The one table of schedule families: each family's name as configs spell it and the reader of
// its parameters, in ScheduleFamily's order (checked below).
struct Family {
  ScheduleFamily family;
  absl::string_view name;
  absl::StatusOr<ScheduleParams> (*parse)(ParamReader&);
};
constexpr Family kFamilies[] = {
    {ScheduleFamily::kIdentity, "identity", ParseIdentity},
    {ScheduleFamily::kContinuousIncrementer, "continuous_incrementer",
     ParseContinuousIncrementer},
    {ScheduleFamily::kSuddenJump, "sudden_jump", ParseSuddenJump},
    {ScheduleFamily::kRandomWalk, "random_walk", ParseRandomWalk},
    {ScheduleFamily::kOrnsteinUhlenbeck, "ornstein_uhlenbeck", ParseOrnsteinUhlenbeck},
    {ScheduleFamily::kPiecewiseConstant, "piecewise_constant", ParsePiecewiseConstant},
    {ScheduleFamily::kSinusoidal, "sinusoidal", ParseSinusoidal},
    {ScheduleFamily::kCosineAnnealing, "cosine_annealing", ParseCosineAnnealing},
    {ScheduleFamily::kSinusoidalJump, "sinusoidal_jump", ParseSinusoidalJump},
    {ScheduleFamily::kPhasedOu, "phased_ou", ParsePhasedOu},
    {ScheduleFamily::kLevyWalk, "levy_walk", ParseLevyWalk},
    {ScheduleFamily::kSequential, "sequential", ParseSequential},
};
// The paper's name for the static stage of a multi-stage schedule.
constexpr absl::string_view kIdentityAlias = "constant";

constexpr bool FamiliesInOrder() {
  if (std::size(kFamilies) != std::variant_size_v<ScheduleParams>) return false;
  for (size_t i = 0; i < std::size(kFamilies); ++i) {
    if (static_cast<size_t>(kFamilies[i].family) != i) return false;
  }
  return true;
}
static_assert(FamiliesInOrder(), "kFamilies lists every ScheduleFamily once, in order");

const Family* FindFamily(absl::string_view name) {
  if (name == kIdentityAlias) return &kFamilies[0];
  for (const Family& family : kFamilies) {
    if (family.name == name) return &family;
  }
  return nullptr;
}

CheckedSchedule CheckSchedule(const ScheduleConfig& config, double min_value, double max_value,
                              uint32_t seed) {
  if (!std::isfinite(min_value) || !std::isfinite(max_value) || min_value >= max_value) {
    return {.problems = {absl::InvalidArgumentError(absl::StrCat(
                "schedule '", config.family, "': bounds must be finite with min < max, got [",
                min_value, ", ", max_value, "]"))}};
  }
  const Family* family = FindFamily(config.family);
  if (family == nullptr) {
    return {.problems = {absl::InvalidArgumentError(absl::StrCat(
                "unknown schedule family '", config.family, "' (known: ", kIdentityAlias, ", ",
                absl::StrJoin(ScheduleFamilyNames(), ", "), ")"))}};
  }
  ParamReader reader(config, min_value, max_value, seed);
  absl::StatusOr<ScheduleParams> params = family->parse(reader);
  reader.Check(params.status());  // a check between parameters, made once each was read
  CheckedSchedule checked{.problems = std::move(reader).Finish()};
  if (checked.problems.empty()) {
    checked.spec = ScheduleSpec{
        .min_value = min_value, .max_value = max_value, .seed = seed, .params = *std::move(params)};
  }
  return checked;
}

}  // namespace

absl::string_view ScheduleFamilyName(ScheduleFamily family) {
  return kFamilies[static_cast<int>(family)].name;
}

std::vector<std::string> ScheduleFamilyNames() {
  std::vector<std::string> names;
  for (const Family& family : kFamilies) names.emplace_back(family.name);
  return names;
}

absl::StatusOr<ScheduleSpec> ParseScheduleSpec(const ScheduleConfig& config, double min_value,
                                               double max_value, uint32_t seed) {
  CheckedSchedule checked = CheckSchedule(config, min_value, max_value, seed);
  if (!checked.problems.empty()) return checked.problems.front();
  return *std::move(checked.spec);
}

std::vector<absl::Status> ScheduleConfigProblems(const ScheduleConfig& config, double min_value,
                                                 double max_value) {
  return CheckSchedule(config, min_value, max_value, /*seed=*/0).problems;
}

}  // namespace dcs::env
