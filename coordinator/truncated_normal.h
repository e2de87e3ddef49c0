// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_TRUNCATED_NORMAL_H_
#define DCS_COORDINATOR_TRUNCATED_NORMAL_H_

// The standard normal distribution in log space, as TPE's Parzen estimators need it
// (optuna/samplers/_tpe/_truncnorm.py): densities of kernels truncated far in a tail must stay
// finite and accurate, so masses are computed as logarithms, with the tail-safe forms Optuna uses.
// Pure functions; thread-safe.

namespace dcs::coordinator {

// ln Φ(x), accurate for every x: an asymptotic series below -20, -Φ(-x) above 6.
double LogNormalCdf(double x);

// ln(Φ(b) - Φ(a)) for a <= b: the mass of [a, b] under the standard normal, computed in the tail
// where a and b lie (-inf when a == b).
double LogNormalMass(double a, double b);

// The x with ln Φ(x) = log_p (log_p <= 0): Newton's method on LogNormalCdf from Boost.Math's
// inverse error function, so that it holds far in the left tail where Φ(x) underflows.
double InverseLogNormalCdf(double log_p);

// The quantile `q` in [0, 1] of the standard normal truncated to [a, b] (a < b), by inverse CDF in
// log space; a for q = 0 and b for q = 1. Where a >= 0 it works with the interval reflected about
// 0, for accuracy in the right tail.
double TruncatedNormalQuantile(double q, double a, double b);

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_TRUNCATED_NORMAL_H_
