// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_PARZEN_ESTIMATOR_H_
#define DCS_COORDINATOR_PARZEN_ESTIMATOR_H_

// TPE's Parzen estimator (Optuna 4.9, optuna/samplers/_tpe/parzen_estimator.py): a mixture of
// product kernels, one per observation plus a prior kernel, over some parameters of a search space
// (one in independent sampling, a group in multivariate sampling).
//
// Each numerical parameter has a working space: its value, or ln(value) for a log range, with
// bounds widened by half a step for grids and integers. A kernel there is a normal truncated
// to the bounds: continuous, or discrete (the mass of the value's grid cell) for grids and
// integers. A categorical parameter's kernel is a row of choice probabilities. Bandwidths
// follow the univariate neighbour rule, or the Scott-like rule of Optuna's multivariate TPE, then
// the magic clip.
//
// An estimator is immutable once fitted; thread-compatible.

#include <vector>

#include "common/random.h"
#include "run/search_space.h"

namespace dcs::coordinator {

struct ParzenOptions {
  double prior_weight = 1.0;  // the prior kernel's weight, and the categorical smoothing
  bool magic_clip = true;     // σ at least range / min(100, N + 2)
  bool endpoints = false;     // the outermost observations' σ may reach to the bounds
  bool multivariate = false;  // Scott-like σ = 0.2·N^(-1/(D+4))·range instead of neighbours
};

// Optuna's default_weights(n): all ones below 25; from 25 on, the oldest n - 25 ramp linearly from
// 1/n to 1 and the newest 25 are 1.
std::vector<double> DefaultWeights(int n);

// One parameter's kernels.
struct ParzenDimension {
  enum class Kind { kContinuous, kDiscrete, kCategorical };
  Kind kind = Kind::kContinuous;
  // Numerical: the working-space bounds, and how values map to it.
  double low = 0;
  double high = 0;
  bool log = false;
  double step = 0;  // a grid's or linear integer range's step, in the value's scale; else 0
  double value_low = 0;  // the distribution's own bounds, for snapping draws
  double value_high = 0;
  // Per kernel (the prior last): centre and bandwidth in working space, ln of the kernel's mass
  // inside [low, high], ln σ and 1/σ, and ln of the factor its density or cell mass is scaled by
  // (continuous: 1 / (σ √(2π) mass); discrete: 1 / mass).
  std::vector<double> mu;
  std::vector<double> sigma;
  std::vector<double> log_mass;
  std::vector<double> log_sigma;
  std::vector<double> inverse_sigma;
  std::vector<double> log_scale;
  // Categorical: per kernel, the probability of each choice, and its ln.
  std::vector<std::vector<double>> probabilities;
  std::vector<std::vector<double>> log_probabilities;
};

class ParzenEstimator {
 public:
  // Fits the mixture to observations given as `columns`, one per parameter of `parameters`, each
  // the values of that parameter in trial order (their weights depend on it), in internal
  // representation. REQUIRES: the parameters are valid (run::ValidateSearchSpace); the columns are
  // as many as the parameters and equally long, each value contained in its distribution.
  ParzenEstimator(const std::vector<const run::SearchParameter*>& parameters,
                  std::vector<std::vector<double>> columns,
                  const ParzenOptions& options);

  // A mixture given kernel by kernel: `weights` (normalised, the prior last) and dimensions laid
  // out and with kernels as dimensions() shows them (the ln constants are recomputed).
  static ParzenEstimator FromKernels(std::vector<double> weights,
                                     std::vector<ParzenDimension> dimensions);

  // `count` draws, one row per draw, internal representation. Draws a component per row from the
  // weights, then each dimension from that component's kernel (truncated-normal draws by inverse
  // CDF, then snapped to the grid).
  std::vector<std::vector<double>> Sample(Random& random, int count) const;

  // ln of the mixture's density (mass, for discrete and categorical dimensions) at each row.
  std::vector<double> LogPdf(const std::vector<std::vector<double>>& points) const;

  // The normalised weights, the prior last.
  const std::vector<double>& weights() const { return weights_; }
  const std::vector<ParzenDimension>& dimensions() const { return dimensions_; }

 private:
  ParzenEstimator() = default;

  std::vector<double> weights_;
  std::vector<double> log_weights_;
  std::vector<ParzenDimension> dimensions_;
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_PARZEN_ESTIMATOR_H_
