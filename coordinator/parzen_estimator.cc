// Copyright 2026 The DCS Authors.
#include "coordinator/parzen_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <variant>

#include "coordinator/truncated_normal.h"

namespace dcs::coordinator {
namespace {

using Kind = ParzenDimension::Kind;

const double kLogSqrt2Pi = 0.5 * std::log(2 * std::numbers::pi);

// The dimension's kind, bounds and value mapping, without kernels.
ParzenDimension Layout(const run::Distribution& distribution) {
  ParzenDimension d;
  if (const auto* f = std::get_if<run::FloatDistribution>(&distribution)) {
    d.value_low = f->low;
    d.value_high = f->high;
    d.log = f->log;
    d.step = f->step.value_or(0.0);
    d.kind = f->step.has_value() ? Kind::kDiscrete : Kind::kContinuous;
    d.low = f->log ? std::log(f->low) : f->low - d.step / 2;
    d.high = f->log ? std::log(f->high) : f->high + d.step / 2;
  } else if (const auto* i = std::get_if<run::IntDistribution>(&distribution)) {
    d.kind = Kind::kDiscrete;
    d.value_low = static_cast<double>(i->low);
    d.value_high = static_cast<double>(i->high);
    d.log = i->log;
    d.step = i->log ? 0.0 : static_cast<double>(i->step);
    // A log integer k's cell is [ln(k - 1/2), ln(k + 1/2)].
    d.low = i->log ? std::log(d.value_low - 0.5) : d.value_low - d.step / 2;
    d.high = i->log ? std::log(d.value_high + 0.5) : d.value_high + d.step / 2;
  } else {
    d.kind = Kind::kCategorical;
  }
  return d;
}

double ToWorking(const ParzenDimension& d, double value) { return d.log ? std::log(value) : value; }

// The value a working-space draw stands for: snapped to the grid, inside the bounds.
double FromWorking(const ParzenDimension& d, double x) {
  double value;
  if (d.kind == Kind::kContinuous) {
    value = d.log ? std::exp(x) : x;
  } else if (d.log) {
    value = std::nearbyint(std::exp(x));  // numpy's round: half to even
  } else {
    value = d.value_low + std::nearbyint((x - d.value_low) / d.step) * d.step;
  }
  return std::clamp(value, d.value_low, d.value_high);
}

// The working-space cell of a discrete value.
std::pair<double, double> Cell(const ParzenDimension& d, double value) {
  if (d.log) return {std::log(value - 0.5), std::log(value + 0.5)};
  return {value - d.step / 2, value + d.step / 2};
}

// Bandwidths of the observation kernels centred at `mus`, before the magic clip.
std::vector<double> NeighbourSigmas(const std::vector<double>& mus, double low, double high,
                                    bool endpoints) {
  const size_t n = mus.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return mus[a] < mus[b]; });
  std::vector<double> sigmas(n);
  for (size_t rank = 0; rank < n; ++rank) {
    const double centre = mus[order[rank]];
    const double left = rank == 0 ? low : mus[order[rank - 1]];
    const double right = rank + 1 == n ? high : mus[order[rank + 1]];
    double sigma = std::max(centre - left, right - centre);
    if (!endpoints && n >= 2) {
      if (rank == 0) sigma = right - centre;
      if (rank + 1 == n) sigma = centre - left;
    }
    sigmas[order[rank]] = sigma;
  }
  return sigmas;
}

// What the densities of the dimension's kernels are computed from, besides centres and
// bandwidths (or choice probabilities).
void SetLogConstants(ParzenDimension& d) {
  if (d.kind == Kind::kCategorical) {
    d.log_probabilities = d.probabilities;
    for (std::vector<double>& row : d.log_probabilities) {
      for (double& p : row) p = std::log(p);
    }
    return;
  }
  d.log_mass.resize(d.mu.size());
  d.log_sigma.resize(d.mu.size());
  d.inverse_sigma.resize(d.mu.size());
  d.log_scale.resize(d.mu.size());
  for (size_t k = 0; k < d.mu.size(); ++k) {
    d.log_mass[k] = LogNormalMass((d.low - d.mu[k]) / d.sigma[k], (d.high - d.mu[k]) / d.sigma[k]);
    d.log_sigma[k] = std::log(d.sigma[k]);
    d.inverse_sigma[k] = 1 / d.sigma[k];
    d.log_scale[k] = -d.log_mass[k];
    if (d.kind == Kind::kContinuous) d.log_scale[k] -= d.log_sigma[k] + kLogSqrt2Pi;
  }
}

void FitNumerical(ParzenDimension& d, std::vector<double> mus, size_t dimensions,
                  const ParzenOptions& options) {
  const double range = d.high - d.low;
  const size_t n = mus.size();
  std::vector<double> sigmas =
      options.multivariate
          ? std::vector<double>(n, 0.2 *
                                       std::pow(static_cast<double>(std::max<size_t>(n, 1)),
                                                -1.0 / (static_cast<double>(dimensions) + 4)) *
                                       range)
          : NeighbourSigmas(mus, d.low, d.high, options.endpoints);
  const double min_sigma =
      options.magic_clip ? range / std::min(100.0, static_cast<double>(n) + 2) : 1e-12;
  for (double& sigma : sigmas) sigma = std::clamp(sigma, min_sigma, range);
  mus.push_back((d.low + d.high) / 2);  // the prior
  sigmas.push_back(range);
  d.mu = std::move(mus);
  d.sigma = std::move(sigmas);
}

void FitCategorical(ParzenDimension& d, const std::vector<double>& observed, size_t choices,
                    const ParzenOptions& options) {
  if (observed.empty()) {
    d.probabilities.assign(1, std::vector<double>(choices, 1.0 / static_cast<double>(choices)));
    return;
  }
  const double smoothing = options.prior_weight / static_cast<double>(observed.size() + 1);
  d.probabilities.assign(observed.size() + 1, std::vector<double>(choices, smoothing));
  for (size_t k = 0; k < observed.size(); ++k) {
    d.probabilities[k][static_cast<size_t>(observed[k])] += 1;
  }
  for (std::vector<double>& row : d.probabilities) {
    const double sum = std::accumulate(row.begin(), row.end(), 0.0);
    for (double& p : row) p /= sum;
  }
}

// A kernel whose ln density falls this far below the mixture's largest term adds less than
// e^-50 of it (times fewer than 10^5 kernels: under 10^-16, below double precision).
constexpr double kNegligible = 50;

// ln of kernel k's density at the working-space point x of a continuous dimension.
double ContinuousLogPdf(const ParzenDimension& d, size_t k, double x) {
  const double z = (x - d.mu[k]) * d.inverse_sigma[k];
  return d.log_scale[k] - 0.5 * z * z;
}

// ln of kernel k's mass of the cell [low, high] (working space) of a discrete dimension.
double DiscreteLogPdf(const ParzenDimension& d, size_t k, double low, double high) {
  return d.log_scale[k] +
         LogNormalMass((low - d.mu[k]) * d.inverse_sigma[k], (high - d.mu[k]) * d.inverse_sigma[k]);
}

// An upper bound of DiscreteLogPdf, without the normal CDF: the cell's width times the largest
// density in it, and at most 1.
double DiscreteLogPdfBound(const ParzenDimension& d, size_t k, double low, double high,
                           double log_width) {
  const double gap = std::max({low - d.mu[k], d.mu[k] - high, 0.0}) * d.inverse_sigma[k];
  return d.log_scale[k] + std::min(0.0, log_width - d.log_sigma[k] - kLogSqrt2Pi - 0.5 * gap * gap);
}

}  // namespace

std::vector<double> DefaultWeights(int n) {
  std::vector<double> weights(static_cast<size_t>(std::max(n, 0)), 1.0);
  if (n < 25) return weights;
  // numpy.linspace(1 / n, 1.0, num=n - 25).
  const int ramp = n - 25;
  for (int i = 0; i < ramp; ++i) {
    weights[static_cast<size_t>(i)] =
        ramp == 1 ? 1.0 / n : 1.0 / n + (1.0 - 1.0 / n) * static_cast<double>(i) / (ramp - 1);
  }
  return weights;
}

ParzenEstimator::ParzenEstimator(const std::vector<const run::SearchParameter*>& parameters,
                                 std::vector<std::vector<double>> columns,
                                 const ParzenOptions& options) {
  const size_t n = columns.empty() ? 0 : columns[0].size();
  if (n == 0) {
    weights_ = {1.0};
  } else {
    weights_ = DefaultWeights(static_cast<int>(n));
    weights_.push_back(options.prior_weight);
    const double sum = std::accumulate(weights_.begin(), weights_.end(), 0.0);
    for (double& w : weights_) w /= sum;
  }
  for (size_t p = 0; p < parameters.size(); ++p) {
    ParzenDimension d = Layout(parameters[p]->distribution);
    std::vector<double>& column = columns[p];
    if (d.kind == Kind::kCategorical) {
      const auto& choices = std::get<run::CategoricalDistribution>(parameters[p]->distribution);
      FitCategorical(d, column, choices.choices.size(), options);
    } else {
      for (double& value : column) value = ToWorking(d, value);
      FitNumerical(d, std::move(column), parameters.size(), options);
    }
    SetLogConstants(d);
    dimensions_.push_back(std::move(d));
  }
  for (const double w : weights_) log_weights_.push_back(std::log(w));
}

ParzenEstimator ParzenEstimator::FromKernels(std::vector<double> weights,
                                             std::vector<ParzenDimension> dimensions) {
  ParzenEstimator estimator;
  estimator.weights_ = std::move(weights);
  for (const double w : estimator.weights_) estimator.log_weights_.push_back(std::log(w));
  for (ParzenDimension& d : dimensions) SetLogConstants(d);
  estimator.dimensions_ = std::move(dimensions);
  return estimator;
}

std::vector<std::vector<double>> ParzenEstimator::Sample(Random& random, int count) const {
  // numpy's choice(p=weights): the first component whose cumulative weight exceeds a uniform.
  std::vector<double> cumulative(weights_.size());
  std::partial_sum(weights_.begin(), weights_.end(), cumulative.begin());
  std::vector<size_t> components(static_cast<size_t>(count));
  for (size_t& component : components) {
    const double u = random.Uniform01() * cumulative.back();
    component = std::min<size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
        weights_.size() - 1);
  }
  std::vector<std::vector<double>> draws(static_cast<size_t>(count),
                                         std::vector<double>(dimensions_.size()));
  for (size_t p = 0; p < dimensions_.size(); ++p) {
    const ParzenDimension& d = dimensions_[p];
    for (size_t i = 0; i < draws.size(); ++i) {
      const size_t k = components[i];
      const double u = random.Uniform01();
      if (d.kind == Kind::kCategorical) {
        const std::vector<double>& row = d.probabilities[k];
        double below = 0;
        size_t choice = 0;
        while (choice + 1 < row.size() && (below += row[choice]) < u) ++choice;
        draws[i][p] = static_cast<double>(choice);
      } else {
        const double a = (d.low - d.mu[k]) / d.sigma[k];
        const double b = (d.high - d.mu[k]) / d.sigma[k];
        draws[i][p] = FromWorking(d, d.mu[k] + d.sigma[k] * TruncatedNormalQuantile(u, a, b));
      }
    }
  }
  return draws;
}

std::vector<double> ParzenEstimator::LogPdf(const std::vector<std::vector<double>>& points) const {
  const size_t kernels = weights_.size();
  std::vector<double> result;
  result.reserve(points.size());
  std::vector<double> terms(kernels);
  std::vector<double> bounds(kernels);
  // Per discrete dimension of the point: its cell, and ln of the cell's width.
  struct PointCell {
    const ParzenDimension* dimension;
    double low, high, log_width;
  };
  std::vector<PointCell> cells;
  for (size_t i = 0; i < points.size(); ++i) {
    const std::vector<double>& point = points[i];
    // Candidates repeat (a categorical has few values): each distinct one is computed once.
    if (const auto same = std::find(points.begin(), points.begin() + i, point);
        same != points.begin() + i) {
      result.push_back(result[same - points.begin()]);
      continue;
    }
    terms = log_weights_;
    cells.clear();
    for (size_t p = 0; p < dimensions_.size(); ++p) {
      const ParzenDimension& d = dimensions_[p];
      if (d.kind == Kind::kCategorical) {
        const auto choice = static_cast<size_t>(point[p]);
        for (size_t k = 0; k < kernels; ++k) terms[k] += d.log_probabilities[k][choice];
      } else if (d.kind == Kind::kContinuous) {
        const double x = ToWorking(d, point[p]);
        for (size_t k = 0; k < kernels; ++k) terms[k] += ContinuousLogPdf(d, k, x);
      } else {
        const auto [low, high] = Cell(d, point[p]);
        cells.push_back({&d, std::max(low, d.low), std::min(high, d.high), 0.0});
        cells.back().log_width = std::log(cells.back().high - cells.back().low);
      }
    }
    if (!cells.empty()) {
      // Cell masses cost far more than their bounds (a series, or two normal CDFs), so only the
      // kernels that can matter get them: those whose bound is within kNegligible of the exact
      // term of the likeliest one.
      for (size_t k = 0; k < kernels; ++k) {
        bounds[k] = terms[k];
        for (const PointCell& c : cells) {
          bounds[k] += DiscreteLogPdfBound(*c.dimension, k, c.low, c.high, c.log_width);
        }
      }
      const auto exact = [&](size_t k) {
        double term = terms[k];
        for (const PointCell& c : cells) term += DiscreteLogPdf(*c.dimension, k, c.low, c.high);
        return term;
      };
      const size_t likeliest = std::max_element(bounds.begin(), bounds.end()) - bounds.begin();
      const double likeliest_term = exact(likeliest);
      for (size_t k = 0; k < kernels; ++k) {
        terms[k] = k == likeliest ? likeliest_term
                   : bounds[k] < likeliest_term - kNegligible
                       ? -std::numeric_limits<double>::infinity()
                       : exact(k);
      }
    }
    const double top = *std::max_element(terms.begin(), terms.end());
    if (top == -std::numeric_limits<double>::infinity()) {
      result.push_back(top);
      continue;
    }
    double sum = 0;
    for (const double term : terms) {
      if (term > top - kNegligible) sum += std::exp(term - top);
    }
    result.push_back(top + std::log(sum));
  }
  return result;
}

}  // namespace dcs::coordinator
