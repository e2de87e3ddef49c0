// Copyright 2026 The DCS Authors.
#include "coordinator/truncated_normal.h"

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <limits>
#include <numbers>

namespace dcs::coordinator {
namespace {

const double kLogSqrt2Pi = 0.5 * std::log(2 * std::numbers::pi);

// Φ(x), from whichever of erf and erfc keeps its relative accuracy at x.
double NormalCdf(double x) {
  const double z = x * std::numbers::sqrt2 / 2;
  if (z < -std::numbers::sqrt2 / 2) return 0.5 * std::erfc(-z);
  if (z < std::numbers::sqrt2 / 2) return 0.5 + 0.5 * std::erf(z);
  return 1.0 - 0.5 * std::erfc(z);
}

// ln(e^p - e^q) for p >= q.
double LogDiff(double log_p, double log_q) { return log_p + std::log1p(-std::exp(log_q - log_p)); }

// ln(e^p + e^q).
double LogSum(double log_p, double log_q) {
  const double high = std::max(log_p, log_q);
  const double low = std::min(log_p, log_q);
  return high + std::log1p(std::exp(low - high));
}

}  // namespace

double LogNormalCdf(double x) {
  if (x > 6) return -NormalCdf(-x);  // ln(1 - u) = -u to double precision
  if (x > -20) return std::log(NormalCdf(x));
  // ln Φ(x) = -x²/2 - ln(-x) - ln √(2π) + ln(1 - 1/x² + 3/x⁴ - 15/x⁶ + ...), summed while the terms
  // still change the total (they shrink until i ≈ x²/2 ≥ 200).
  const double inverse_square = 1 / (x * x);
  double total = 1;
  double previous = 0;
  double term = 1;
  for (int i = 1; total != previous; ++i) {
    previous = total;
    term *= -(2 * i - 1) * inverse_square;
    total += term;
  }
  return -0.5 * x * x - std::log(-x) - kLogSqrt2Pi + std::log(total);
}

// ln(Φ(b) - Φ(a)) for a narrow interval, |a + b|·(b - a) <= 4 and b - a <= 2: with m its
// midpoint and h its half-width, the mass is 2h·φ(m)·S, S = Σ_k He_2k(m) h^2k / (2k + 1)!
// (integrating the Hermite generating function e^(-mu - u²/2) = Σ He_n(m) (-u)^n / n! over
// [-h, h]). The terms fall at least as (|m|h)^2k / (2k)!, so a dozen reach double precision:
// cheaper than the two normal CDFs, and free of their cancellation.
double LogNarrowNormalMass(double a, double b) {
  const double m = (a + b) / 2;
  const double h = (b - a) / 2;
  const double h2 = h * h;
  // He_{n+1} = m He_n - n He_{n-1}; two steps per term.
  double even = 1;   // He_2k, from He_0
  double he = m;     // He_2k+1, from He_1
  double power = 1;  // h^2k / (2k + 1)!
  double sum = 0;    // S - 1
  double previous_term = 1;
  for (int k = 1; k <= 40; ++k) {
    // He_2k from He_{2k-1} (he) and He_{2k-2} (even), then He_{2k+1}.
    const int n = 2 * k - 1;
    const double he_2k = m * he - n * even;
    const double he_2k1 = m * he_2k - (n + 1) * he;
    even = he_2k;
    he = he_2k1;
    power *= h2 / ((2 * k) * (2 * k + 1));
    const double term = even * power;
    sum += term;
    // Two in a row: one He_2k(m) alone may vanish (He_2(1) = 0), two neighbours cannot.
    const double tolerance = 1e-17 * std::abs(1 + sum);
    if (std::abs(term) <= tolerance && std::abs(previous_term) <= tolerance) break;
    previous_term = term;
  }
  return -0.5 * m * m - kLogSqrt2Pi + std::log(2 * h) + std::log1p(sum);
}

double LogNormalMass(double a, double b) {
  if (b - a <= 2 && std::abs(a + b) * (b - a) <= 4) return LogNarrowNormalMass(a, b);
  if (b <= 0 && b > -20) {
    // LogDiff of the two ln Φ without their exp: Φ(b) is a normal double here.
    // Where Φ(a) <= Φ(b)/2 the difference is exact to an ulp (no cancellation).
    const double cdf_b = NormalCdf(b);
    const double cdf_a = NormalCdf(a);
    if (cdf_a <= 0.5 * cdf_b) return std::log(cdf_b - cdf_a);
    return std::log(cdf_b) + std::log1p(-cdf_a / cdf_b);
  }
  if (b <= 0) return LogDiff(LogNormalCdf(b), LogNormalCdf(a));
  if (a > 0) return LogNormalMass(-b, -a);
  return std::log1p(-NormalCdf(a) - NormalCdf(-b));
}

double InverseLogNormalCdf(double log_p) {
  if (log_p >= 0) return std::numeric_limits<double>::infinity();
  if (log_p == -std::numeric_limits<double>::infinity())
    return -std::numeric_limits<double>::infinity();
  // A first guess from the inverse error function, on the side of 1/2 where p or 1 - p keeps its
  // digits; beyond the smallest double, the leading term of the tail, -√(-2 ln p).
  double x;
  if (log_p < std::log(std::numeric_limits<double>::min())) {
    x = -std::sqrt(-2 * log_p);
  } else if (log_p < -std::numbers::ln2) {
    x = -std::numbers::sqrt2 * boost::math::erfc_inv(2 * std::exp(log_p));
  } else {
    x = std::numbers::sqrt2 * boost::math::erfc_inv(-2 * std::expm1(log_p));
  }
  // Newton's method on ln Φ(x) - log_p, whose derivative is φ(x)/Φ(x).
  for (int i = 0; i < 50; ++i) {
    const double log_cdf = LogNormalCdf(x);
    const double step = (log_cdf - log_p) / std::exp(-0.5 * x * x - kLogSqrt2Pi - log_cdf);
    x -= step;
    if (std::abs(step) <= 1e-15 * std::max(1.0, std::abs(x))) break;
  }
  return x;
}

double TruncatedNormalQuantile(double q, double a, double b) {
  if (q <= 0) return a;
  if (q >= 1) return b;
  const double log_mass = LogNormalMass(a, b);
  const double x = a < 0
                       ? InverseLogNormalCdf(LogSum(LogNormalCdf(a), std::log(q) + log_mass))
                       : -InverseLogNormalCdf(LogSum(LogNormalCdf(-b), std::log1p(-q) + log_mass));
  return std::clamp(x, a, b);
}

}  // namespace dcs::coordinator
