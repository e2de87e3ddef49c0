// Copyright 2026 The DCS Authors.
//
// The random sampler of coordinator/sampler.h.

#include <algorithm>
#include <cmath>
#include <variant>

#include "coordinator/sampler.h"

namespace dcs::coordinator {
namespace {

class RandomSampler : public Sampler {
 public:
  explicit RandomSampler(uint64_t seed) : seed_(seed) {}

  run::ParameterValues Sample(const run::SearchSpace& space, const std::vector<StudyTrial>&,
                              int64_t number) const override {
    Random random(StreamSeed(seed_, "trial", {static_cast<uint64_t>(number)}));
    return RandomValues(space, random);
  }

 private:
  uint64_t seed_;
};

// A uniform draw over [low, high) snapped to the grid low + k·step, inside [low, high].
double OnGrid(double low, double high, double step, Random& random) {
  const double x = random.Uniform(low - step / 2, high + step / 2);
  return std::clamp(low + std::nearbyint((x - low) / step) * step, low, high);
}

}  // namespace

double RandomValue(const run::Distribution& distribution, Random& random) {
  if (const auto* f = std::get_if<run::FloatDistribution>(&distribution)) {
    if (f->step.has_value()) return OnGrid(f->low, f->high, *f->step, random);
    if (f->low == f->high) return f->low;
    const double x = f->log ? std::exp(random.Uniform(std::log(f->low), std::log(f->high)))
                            : random.Uniform(f->low, f->high);
    return std::clamp(x, f->low, std::nextafter(f->high, f->low));  // below high, as Optuna's
  }
  if (const auto* i = std::get_if<run::IntDistribution>(&distribution)) {
    const double low = static_cast<double>(i->low);
    const double high = static_cast<double>(i->high);
    if (!i->log) return OnGrid(low, high, static_cast<double>(i->step), random);
    const double x = random.Uniform(std::log(low - 0.5), std::log(high + 0.5));
    return std::clamp(std::nearbyint(std::exp(x)), low, high);
  }
  const auto& choices = std::get<run::CategoricalDistribution>(distribution).choices;
  return static_cast<double>(random.Integers(0, static_cast<int64_t>(choices.size())));
}

run::ParameterValues RandomValues(const run::SearchSpace& space, Random& random) {
  run::ParameterValues values;
  for (const run::SearchParameter& parameter : space.parameters) {
    if (run::IsActive(parameter, space, values)) {
      values[parameter.name] = RandomValue(parameter.distribution, random);
    }
  }
  return values;
}

std::unique_ptr<Sampler> MakeRandomSampler(uint64_t seed) {
  return std::make_unique<RandomSampler>(seed);
}

}  // namespace dcs::coordinator
