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

// The longest interval or period a config may give, in steps.
constexpr double kMaxSteps = 1e12;

std::string FormatBound(double value) {
  return std::isinf(value) ? (value > 0 ? "inf" : "-inf") : absl::StrCat(value);
}

// "in [lo, hi]", as errors give a range.
std::string RangeText(double lo, double hi) {
  return absl::StrCat("in [", FormatBound(lo), ", ", FormatBound(hi), "]");
}

// Reads one schedule config's parameters, remembering which it has read, so that Finish() can
// name any it did not recognise, and keeping every problem found (Check), so that each
// parameter is checked whatever the others' checks found. Every error names the family and the
// parameter, and carries the parameter as its field (common/status_util.h).
//
// With `reference`, each reading method also adds its parameter there as docs/config.md shows
// it (its kind, default and range, from the arguments it checks with, and its meaning): a
// family's reader run once on a config without parameters describes them all
// (ScheduleFamilyReference). Ranges given by the schedule's bounds read "min" and "max".
class ParamReader {
 public:
  ParamReader(const ScheduleConfig& config, double min_value, double max_value, uint32_t seed,
              std::vector<KeyDoc>* reference = nullptr)
      : config_(config), min_(min_value), max_(max_value), seed_(seed), reference_(reference) {}

  const ScheduleConfig& config() const { return config_; }
  double min() const { return min_; }
  double max() const { return max_; }
  uint32_t seed() const { return seed_; }
  double span() const { return max_ - min_; }
  double midpoint() const { return 0.5 * (min_ + max_); }

  // A number in [lo, hi], `fallback` if absent (nullopt: required).
  absl::Status Number(const std::string& name, absl::string_view meaning,
                      std::optional<double> fallback, double lo, double hi, double* out) {
    Describe(name, "number", Default(fallback), RangeText(lo, hi), meaning);
    return ReadNumber(name, fallback, lo, hi, out);
  }

  // A non-negative magnitude, given as `name` (absolute) or `fraction_name` (times
  // `scale` * span); `fallback_fraction` if neither (nullopt: required).
  absl::Status Magnitude(const std::string& name, const std::string& fraction_name, double scale,
                         absl::string_view meaning, std::optional<double> fallback_fraction,
                         double* out) {
    Describe(absl::StrCat(name, ", ", fraction_name),
             absl::StrCat("magnitude (of span", scale == 1 ? "" : absl::StrCat("/", 1 / scale),
                          ")"),
             fallback_fraction.has_value()
                 ? absl::StrCat(fraction_name, " ", *fallback_fraction)
                 : "required",
             RangeText(0, kInf), meaning);
    Allow(name, fraction_name);
    const bool absolute = Has(name);
    const bool fraction = Has(fraction_name);
    if (absolute && fraction) return BothGiven(name, fraction_name);
    if (absolute) return ReadNumber(name, std::nullopt, 0, kInf, out);
    double f = 0;
    if (!fraction && !fallback_fraction.has_value()) {
      return Error(name, absl::StrCat("missing (give ", name, " or ", fraction_name, ")"));
    }
    DCS_RETURN_IF_ERROR(ReadNumber(fraction_name, fallback_fraction, 0, kInf, &f));
    *out = f * scale * span();
    return absl::OkStatus();
  }

  // A range [lo, hi] of non-negative magnitudes, absolute or as fractions of the span.
  absl::Status MagnitudeRange(const std::string& name, const std::string& fraction_name,
                              absl::string_view meaning, Range fallback_fraction, Range* out) {
    Describe(absl::StrCat(name, ", ", fraction_name), "magnitude range (of span)",
             absl::StrCat(fraction_name, " [", fallback_fraction.lo, ", ", fallback_fraction.hi,
                          "]"),
             "0 <= lo <= hi", meaning);
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
  absl::Status Interval(const std::string& name, absl::string_view meaning, StepRange fallback,
                        StepRange* out) {
    Describe(name, "interval", absl::StrCat("[", fallback.lo, ", ", fallback.hi, "]"),
             "1 <= lo <= hi", meaning);
    Allow(name);
    *out = fallback;
    if (!Has(name)) return absl::OkStatus();
    double lo = 0;
    double hi = 0;
    DCS_RETURN_IF_ERROR(Pair(name, &lo, &hi));
    if (lo != std::floor(lo) || hi != std::floor(hi) || lo < 1 || lo > hi || hi > kMaxSteps) {
      return Error(name, absl::StrCat("must be [lo, hi] in whole steps with 1 <= lo <= hi, got [",
                                      lo, ", ", hi, "]"));
    }
    *out = {static_cast<int64_t>(lo), static_cast<int64_t>(hi)};
    return absl::OkStatus();
  }

  // A whole number >= `lo`.
  absl::Status Steps(const std::string& name, absl::string_view meaning,
                     std::optional<int64_t> fallback, int64_t lo, int64_t* out) {
    Describe(name, "integer", fallback.has_value() ? absl::StrCat(*fallback) : "required",
             RangeText(static_cast<double>(lo), kMaxSteps), meaning);
    double value = 0;
    DCS_RETURN_IF_ERROR(ReadNumber(
        name, fallback.has_value() ? std::optional<double>(*fallback) : std::nullopt,
        static_cast<double>(lo), kMaxSteps, &value));
    if (value != std::floor(value)) {
      return Error(name, absl::StrCat("must be a whole number of steps, got ", value));
    }
    *out = static_cast<int64_t>(value);
    return absl::OkStatus();
  }

  // One of `choices`, by name; `fallback` if absent.
  template <typename T>
  absl::Status Choice(const std::string& name, absl::string_view meaning, T fallback,
                      const std::vector<std::pair<std::string, T>>& choices, T* out) {
    std::vector<std::string> names;
    std::string fallback_name;
    for (const auto& [choice_name, value] : choices) {
      names.push_back(choice_name);
      if (value == fallback) fallback_name = choice_name;
    }
    Describe(name, absl::StrCat("one of {", absl::StrJoin(names, ", "), "}"), fallback_name, "",
             meaning);
    const ScheduleParam* param = Take(name);
    *out = fallback;
    if (param == nullptr) return absl::OkStatus();
    const std::string* word = std::get_if<std::string>(param);
    for (const auto& [choice_name, value] : choices) {
      if (word != nullptr && *word == choice_name) {
        *out = value;
        return absl::OkStatus();
      }
    }
    return Error(name, absl::StrCat("must be one of ", absl::StrJoin(names, ", ")));
  }

  // A non-empty list of values within the schedule's bounds; `fallback` if absent (nullopt:
  // required), which `fallback_text` states in terms of the bounds.
  absl::Status Values(const std::string& name, absl::string_view meaning,
                      std::optional<std::vector<double>> fallback,
                      absl::string_view fallback_text, std::vector<double>* out) {
    Describe(name, "list of numbers",
             fallback.has_value() ? std::string(fallback_text) : "required",
             "each in [min, max]", meaning);
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
  absl::Status OptionalValue(const std::string& name, absl::string_view meaning,
                             std::optional<double>* out) {
    Describe(name, "number", "none", "in [min, max]", meaning);
    Allow(name);
    if (!Has(name)) return absl::OkStatus();
    double value = 0;
    DCS_RETURN_IF_ERROR(ReadNumber(name, std::nullopt, min_, max_, &value));
    *out = value;
    return absl::OkStatus();
  }

  // A level within the schedule's bounds: `name` in absolute units, the word "initial" (the
  // episode-initial value: `*initial` set), or `fraction_name`, a fraction of the span above the
  // minimum; `fallback_fraction` if none is given.
  absl::Status LevelOrInitial(const std::string& name, const std::string& fraction_name,
                              absl::string_view meaning, double fallback_fraction, double* out,
                              bool* initial) {
    Describe(absl::StrCat(name, ", ", fraction_name),
             absl::StrCat("number, initial, or ", fraction_name, " (of span, from min)"),
             absl::StrCat(fraction_name, " ", fallback_fraction),
             absl::StrCat("in [min, max]; ", fraction_name, " ", RangeText(0, 1)), meaning);
    Allow(name, fraction_name);
    const ScheduleParam* level = Take(name);
    if (level != nullptr && Has(fraction_name)) return BothGiven(name, fraction_name);
    if (const std::string* word = level == nullptr ? nullptr : std::get_if<std::string>(level)) {
      if (*word != "initial") return Error(name, "must be a number or 'initial'");
      *initial = true;
      return absl::OkStatus();
    }
    if (level != nullptr) return ReadNumber(name, std::nullopt, min_, min_ + span(), out);
    double fraction = fallback_fraction;
    absl::Status status = ReadNumber(fraction_name, fallback_fraction, 0, 1, &fraction);
    *out = min_ + fraction * span();
    return status;
  }

  // The parts of a sequential schedule (required).
  const std::vector<ScheduleConfig>& Parts(absl::string_view meaning) {
    Describe("parts", "list of schedules", "required", "", meaning);
    return config_.parts;
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
  // Number's reading, for the methods that describe their parameter otherwise.
  absl::Status ReadNumber(const std::string& name, std::optional<double> fallback, double lo,
                          double hi, double* out) {
    const ScheduleParam* param = Take(name);
    if (param == nullptr) {
      if (!fallback.has_value()) return Error(name, "missing");
      *out = *fallback;
      return absl::OkStatus();
    }
    const double* value = std::get_if<double>(param);
    if (value == nullptr) return Error(name, "must be a number");
    return InRange(name, *value, lo, hi, out);
  }

  static std::string Default(std::optional<double> fallback) {
    return fallback.has_value() ? absl::StrCat(*fallback) : "required";
  }

  // Adds a parameter to the reference, if one is being made.
  void Describe(std::string name, std::string type, std::string default_value, std::string range,
                absl::string_view meaning) {
    if (reference_ == nullptr) return;
    reference_->push_back({.name = std::move(name),
                           .type = std::move(type),
                           .default_value = std::move(default_value),
                           .range = std::move(range),
                           .meaning = std::string(meaning)});
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
  std::vector<KeyDoc>* const reference_;
  std::set<std::string> known_;
  std::vector<absl::Status> problems_;
};

const std::vector<std::pair<std::string, Direction>> kDirections = {
    {"positive", Direction::kPositive}, {"negative", Direction::kNegative},
    {"both", Direction::kBoth}};
const std::vector<std::pair<std::string, EdgeMode>> kEdgeModes = {{"clip", EdgeMode::kClip},
                                                                  {"reflect", EdgeMode::kReflect}};

// Meanings shared by several families.
constexpr absl::string_view kPeriodMeaning = "steps of one full wave";
constexpr absl::string_view kStepStdMeaning =
    "standard deviation of the Gaussian change added each step";
constexpr absl::string_view kJumpSizeMeaning = "size of each jump, drawn uniformly";
constexpr absl::string_view kJumpIntervalMeaning = "steps between jumps";
constexpr absl::string_view kDirectionProbMeaning = "probability of +1 when direction is both";
constexpr absl::string_view kThetaMeaning = "rate of reversion per step";
constexpr absl::string_view kSigmaMeaning = "standard deviation of each step's noise";

absl::StatusOr<ScheduleParams> ParseSinusoidal(ParamReader& r) {
  SinusoidalParams p;
  using D = SinusoidalParams::InitialDirection;
  r.Check(r.Magnitude("amplitude", "amplitude_frac", 0.5,
                      "the wave's peak distance from the episode-initial value", 0.0,
                      &p.amplitude));
  // The default was 0, which the wave reads as 1 (a period of one step): the same schedule.
  r.Check(r.Number("period", kPeriodMeaning, 1.0, 1, kInf, &p.period));
  r.Check(r.Choice("initial_direction", "which way the value moves first", D::kRandom,
                   {{"random", D::kRandom}, {"down", D::kDown}, {"up", D::kUp}},
                   &p.initial_direction));
  return p;
}

absl::StatusOr<ScheduleParams> ParseCosineAnnealing(ParamReader& r) {
  using P = CosineAnnealingParams;
  P p;
  r.Check(r.Choice("mode",
                   "cycle: a new cycle every T_0 * T_mult^i steps, retargeted; once: one "
                   "cycle of T_max steps",
                   P::Mode::kCycle, {{"cycle", P::Mode::kCycle}, {"once", P::Mode::kOnce}},
                   &p.mode));
  r.Check(r.Steps("T_0", "the first cycle's length in steps (mode cycle; once needs none)",
                  p.mode == P::Mode::kOnce ? std::optional<int64_t>(200) : std::nullopt, 1,
                  &p.t_0));
  r.Check(r.Steps("T_mult", "each cycle's length over the one before", 1, 1, &p.t_mult));
  r.Check(r.Steps("T_max", "the cycle's length in steps (mode once)", 1000, 1, &p.t_max));
  r.Check(r.OptionalValue("start", "the first cycle's start; none: the episode-initial value",
                          &p.start));
  r.Check(r.OptionalValue("end", "mode once's target; none: an edge chosen by direction",
                          &p.end));
  if (p.end.has_value() && p.mode != P::Mode::kOnce) {
    return r.Error("end", "applies to mode once only (cycles choose their end by direction)");
  }
  double radius = 0;
  r.Check(r.Magnitude("neighborhood_radius", "neighborhood_radius_frac", 0.5,
                      "each cycle stays this close to its start; 0: anywhere in the range", 0.0,
                      &radius));
  if (radius > 0) p.neighborhood_radius = radius;
  r.Check(r.Number("min_delta", "the least distance from a cycle's start to its end", 0.0, 0,
                   kInf, &p.min_delta));
  r.Check(r.Choice("direction",
                   "the edge a cycle heads for: auto, the farther one; to_min; to_max; random",
                   P::EndDirection::kAuto,
                   {{"auto", P::EndDirection::kAuto},
                    {"to_min", P::EndDirection::kToMin},
                    {"to_max", P::EndDirection::kToMax},
                    {"random", P::EndDirection::kRandom}},
                   &p.direction));
  r.Check(r.Choice("retarget",
                   "where the next cycle starts: swap, the last one's end; restart, the "
                   "episode's start; random, either",
                   P::Retarget::kRestart,
                   {{"swap", P::Retarget::kSwap},
                    {"restart", P::Retarget::kRestart},
                    {"random", P::Retarget::kRandom}},
                   &p.retarget));
  r.Check(r.Number("repel_edge_eps_frac",
                   "a start this close to an edge (a fraction of the band) heads for the other",
                   0.05, 0, 0.5, &p.repel_edge_eps_frac));
  return p;
}

absl::StatusOr<ScheduleParams> ParseContinuousIncrementer(ParamReader& r) {
  using P = ContinuousIncrementerParams;
  P p;
  r.Check(r.Magnitude("delta", "delta_frac", 1.0, "the change each step", std::nullopt,
                      &p.delta));
  r.Check(r.Choice("direction", "the sign of each step; both: drawn by direction_prob",
                   Direction::kBoth, kDirections, &p.direction));
  r.Check(r.Number("direction_prob", kDirectionProbMeaning, 0.5, 0, 1, &p.direction_prob));
  r.Check(r.Choice("edge_mode", "a step past a bound: clipped, or reflected (the sign flips)",
                   EdgeMode::kReflect, kEdgeModes, &p.edge_mode));
  r.Check(r.Choice("episode_direction", "the sign fixed at each reset; none: per step",
                   P::EpisodeDirection::kRandom,
                   {{"none", P::EpisodeDirection::kNone},
                    {"up", P::EpisodeDirection::kUp},
                    {"down", P::EpisodeDirection::kDown},
                    {"random", P::EpisodeDirection::kRandom}},
                   &p.episode_direction));
  r.Check(r.Number("noise_std", "standard deviation of Gaussian noise added each step", 0.0, 0,
                   kInf, &p.noise_std));
  double follow = 0;
  r.Check(r.Number("follow_predefined_prob",
                   "probability that a step keeps the sign (else it reverses)", 0.8, 0, 1,
                   &follow));
  p.follow_predefined_prob = follow;
  return p;
}

absl::StatusOr<ScheduleParams> ParseRandomWalk(ParamReader& r) {
  RandomWalkParams p;
  r.Check(r.Magnitude("std", "std_frac", 1.0, kStepStdMeaning, 0.01, &p.std));
  return p;
}

absl::StatusOr<ScheduleParams> ParsePiecewiseConstant(ParamReader& r) {
  PiecewiseConstantParams p;
  r.Check(r.Values("values", "the levels; each interval holds one drawn uniformly", std::nullopt,
                   "", &p.values));
  r.Check(r.Interval("interval_range", "steps a level is held", {30, 50}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParseSuddenJump(ParamReader& r) {
  SuddenJumpParams p;
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range", kJumpSizeMeaning,
                           {0.1, 0.3}, &p.step_size));
  r.Check(r.Interval("interval_range", kJumpIntervalMeaning, {10, 30}, &p.interval));
  r.Check(r.Choice("direction", "the sign of each jump; both: drawn by direction_prob",
                   Direction::kBoth, kDirections, &p.direction));
  r.Check(r.Number("direction_prob", kDirectionProbMeaning, 0.5, 0, 1, &p.direction_prob));
  r.Check(r.Choice("edge_mode", "a jump past a bound: clipped, or reflected", EdgeMode::kClip,
                   kEdgeModes, &p.edge_mode));
  return p;
}

absl::StatusOr<ScheduleParams> ParseOrnsteinUhlenbeck(ParamReader& r) {
  OrnsteinUhlenbeckParams p;
  r.Check(r.Number("theta", kThetaMeaning, 0.05, 0, 1, &p.theta));
  r.Check(r.Magnitude("sigma", "sigma_frac", 1.0, kSigmaMeaning, 0.08, &p.sigma));
  r.Check(r.LevelOrInitial("mu", "mu_frac",
                           "the level reverted to; initial: the episode-initial value (the "
                           "paper's variant)",
                           0.5, &p.mu, &p.mu_is_episode_initial));
  return p;
}

absl::StatusOr<ScheduleParams> ParseSinusoidalJump(ParamReader& r) {
  SinusoidalJumpParams p;
  r.Check(r.Magnitude("amplitude", "amplitude_frac", 0.5,
                      "the wave's peak distance from its baseline", 0.3, &p.amplitude));
  r.Check(r.Number("period", kPeriodMeaning, 100.0, 1, kInf, &p.period));
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range",
                           "size of each jump of the baseline, drawn uniformly", {0.2, 0.4},
                           &p.step_size));
  r.Check(r.Interval("interval_range", kJumpIntervalMeaning, {80, 150}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParsePhasedOu(ParamReader& r) {
  const double min_value = r.min();
  PhasedOuParams p;
  r.Check(r.Number("theta", kThetaMeaning, 0.05, 0, 1, &p.theta));
  r.Check(r.Magnitude("sigma", "sigma_frac", 1.0, kSigmaMeaning, 0.04, &p.sigma));
  r.Check(r.Values("values", "the anchors reverted to; each interval holds one drawn uniformly",
                   std::vector<double>{min_value, r.midpoint(), min_value + r.span()},
                   "[min, midpoint, max]", &p.values));
  r.Check(r.Interval("interval_range", "steps an anchor is held", {100, 150}, &p.interval));
  return p;
}

absl::StatusOr<ScheduleParams> ParseLevyWalk(ParamReader& r) {
  LevyWalkParams p;
  r.Check(r.Magnitude("std", "std_frac", 1.0, kStepStdMeaning, 0.008, &p.std));
  r.Check(r.MagnitudeRange("step_size_range", "step_size_frac_range", kJumpSizeMeaning,
                           {0.2, 0.4}, &p.step_size));
  r.Check(r.Interval("interval_range", kJumpIntervalMeaning, {40, 80}, &p.interval));
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
  const std::vector<ScheduleConfig>& parts =
      r.Parts("schedules applied in order each step, each to the value the one before made");
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

std::vector<ScheduleFamilyDoc> ScheduleFamilyReference() {
  std::vector<ScheduleFamilyDoc> families;
  for (const Family& family : kFamilies) {
    ScheduleFamilyDoc& doc = families.emplace_back();
    doc.name = std::string(family.name);
    if (family.family == ScheduleFamily::kIdentity) doc.alias = std::string(kIdentityAlias);
    const ScheduleConfig config{.family = doc.name};
    ParamReader reader(config, 0, 1, 0, &doc.parameters);
    // Each parameter is described as it is read; a required one is missing here.
    family.parse(reader).status().IgnoreError();
  }
  return families;
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
