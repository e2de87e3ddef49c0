// Copyright 2026 The DCS Authors.
#ifndef DCS_ENV_CONTEXT_POOL_H_
#define DCS_ENV_CONTEXT_POOL_H_

// Context pools: the finite set of values an episode's initial context c_0 is drawn from, one
// draw at every reset (docs/reference.md, "Pools"). Immutable; thread-safe.
//
// Pool-N over [lo, hi] follows the paper's recursive midpoint insertion: pool-1 is the midpoint,
// pool-3 adds the two extremes, pool-5 inserts the midpoints between neighbours, and so on
// (sizes 1, 3, 5, 9, 17, ...). The paper's other sizes (7, 15, 31, 61) cannot arise that way; as
// the reference does, they are N evenly spaced values (linspace), which is also what midpoint
// insertion gives for its own sizes. The paper's CartPole pool-7, written with two decimals
// (0.35, 0.41, 0.48, 0.55, 0.62, 0.68, 0.75), is an explicit list.

#include <cstdint>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"

namespace dcs::env {

class ContextPool {
 public:
  // How an episode picks its value: a uniform draw from the slot's random stream, or the
  // reference's round robin over the pool rotated by the slot (value (episode + slot) mod N).
  enum class Selection { kRandom, kRoundRobin };

  // Pool-N over [lo, hi] (see the file comment). INVALID_ARGUMENT unless lo <= hi, both finite,
  // and 1 <= size <= 10000.
  static absl::StatusOr<ContextPool> OfSize(double lo, double hi, int size);

  // Exactly these values. INVALID_ARGUMENT if empty or not finite.
  static absl::StatusOr<ContextPool> OfValues(std::vector<double> values);

  const std::vector<double>& values() const { return values_; }

  // The value of episode `episode` of slot `slot`; `random` is used for kRandom only.
  double Select(Selection selection, uint64_t episode, uint64_t slot, Random& random) const;

 private:
  explicit ContextPool(std::vector<double> values) : values_(std::move(values)) {}

  std::vector<double> values_;  // ascending for OfSize; as given for OfValues
};

// The paper's recursive midpoint insertion over [lo, hi] down to `levels` levels: level 0 is
// {mid}, level 1 {lo, mid, hi}, then each level inserts the midpoints of neighbours
// (2^levels + 1 values for levels >= 1).
std::vector<double> MidpointInsertion(double lo, double hi, int levels);

}  // namespace dcs::env

#endif  // DCS_ENV_CONTEXT_POOL_H_
