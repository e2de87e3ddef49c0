// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_RANDOM_H_
#define DCS_COMMON_RANDOM_H_

// The one random-number generator of DCS: numpy.random.Generator(PCG64(seed)) draws (numpy 1.24),
// bit-exact for random(), uniform() and integers() so that seeds reproduce Gymnasium's and the
// reference schedules' streams (numpy's default_rng; docs/reference.md, "Schedule families"), plus
// the seed derivations every randomness source goes through: named counter-based streams
// (docs/architecture.md §6) and the reference schedules' per-episode generator. Random is
// thread-compatible and a value type: a copy continues the same stream independently. The free
// functions are thread-safe.

#include <cassert>
#include <cstdint>
#include <initializer_list>

#include "absl/strings/string_view.h"
#include "common/pcg64.h"
#include "common/seed_sequence.h"

namespace dcs {

class Random {
 public:
  // Generator(PCG64(seed)).
  explicit Random(const SeedSequence& seed) : bits_(seed) {}
  // numpy.random.default_rng(seed) for an integer seed: Generator(PCG64(SeedSequence(seed))).
  explicit Random(uint64_t seed) : Random(SeedSequence({seed})) {}

  // Generator.random(): a double in [0, 1), (Next64() >> 11)·2^-53. One 64-bit draw.
  double Uniform01() { return static_cast<double>(bits_.Next64() >> 11) * 0x1.0p-53; }

  // Generator.uniform(lo, hi): lo + (hi - lo)·Uniform01(), with numpy's two roundings. In
  // [lo, hi) up to rounding; lo when lo == hi. One 64-bit draw. REQUIRES: hi - lo is finite.
  // Bit-exactness needs the product and the sum rounded separately, never fused into an FMA:
  // the product has its own statement (enough for clang's default -ffp-contract=on), and GCC in
  // ISO mode (-std=c++20, as DCS builds) does not contract; -ffp-contract=fast with an
  // FMA-capable -march would break it (the CartPole reset test in random_test.cc catches that).
  double Uniform(double lo, double hi) {
    const double range = hi - lo;
    const double scaled = range * Uniform01();
    return lo + scaled;
  }

  // Generator.integers(lo, hi): uniform in [lo, hi), bit-exact with numpy for every range.
  // A range of one value (hi == lo + 1) returns lo and draws nothing. A range of at most 2^32
  // values draws one or more Next32() (Lemire's method with rejection); a wider one draws Next64()
  // values. REQUIRES: lo < hi.
  int64_t Integers(int64_t lo, int64_t hi) {
    assert(lo < hi);
    // numpy's rng = hi - 1 - lo and off = lo, as wrapping unsigned arithmetic.
    const uint64_t max_offset = static_cast<uint64_t>(hi) - static_cast<uint64_t>(lo) - 1;
    const uint64_t offset = max_offset < 0xFFFFFFFF ? Lemire32(static_cast<uint32_t>(max_offset))
                                                    : WideOffset(max_offset);
    return static_cast<int64_t>(static_cast<uint64_t>(lo) + offset);
  }

  // Statistically N(mean, stddev^2) by the Marsaglia polar method (not numpy's ziggurat, so not
  // numpy's values). Each accepted pair of Uniform01() draws yields two normals; the second is
  // kept (part of this generator's state, copied with it) and returned by the next call.
  // REQUIRES: stddev >= 0.
  double Normal(double mean, double stddev) {
    if (has_spare_normal_) {
      has_spare_normal_ = false;
      return mean + stddev * spare_normal_;
    }
    return mean + stddev * StandardNormalPair();
  }

  // True with probability p: Uniform01() < p (numpy's `rng.random() < p`). One 64-bit draw, also
  // when p <= 0 (never true) or p >= 1 (always true).
  bool Bernoulli(double p) { return Uniform01() < p; }

 private:
  // numpy's buffered_bounded_lemire_uint32 for max_offset < 2^32 - 1: a value in [0, max_offset].
  uint64_t Lemire32(uint32_t max_offset) {
    if (max_offset == 0) return 0;  // no draw
    const uint64_t range = uint64_t{max_offset} + 1;
    uint64_t m = uint64_t{bits_.Next32()} * range;
    if (static_cast<uint32_t>(m) < range) m = Lemire32Reject(m, max_offset);
    return m >> 32;
  }
  // The rejection loop of Lemire32, given the first product `m` (rarely taken).
  uint64_t Lemire32Reject(uint64_t m, uint32_t max_offset);
  // numpy's paths for max_offset >= 2^32 - 1: one Next32(), or 64-bit Lemire on Next64().
  uint64_t WideOffset(uint64_t max_offset);
  // Draws two standard normals; returns one and keeps the other as the spare.
  double StandardNormalPair();

  Pcg64 bits_;
  double spare_normal_ = 0.0;  // a standard normal, valid when has_spare_normal_
  bool has_spare_normal_ = false;
};

// FNV-1a, 64-bit (offset basis 0xcbf29ce484222325, prime 0x100000001b3) of the bytes of `name`:
// the stable hash that turns a stream name into a seed word. Never change it: run seeds persist.
uint64_t Fnv1a64(absl::string_view name);

// The seed of a named, counter-based stream (docs/architecture.md §6), e.g. StreamSeed(run_seed,
// "slot", {i}) or StreamSeed(run_seed, "eval", {context, episode}): SeedSequence({seed,
// Fnv1a64(name), indices...}). Equal inputs give equal seeds; changing any input gives an unrelated
// stream.
SeedSequence StreamSeed(uint64_t seed, absl::string_view name,
                        std::initializer_list<uint64_t> indices = {});

// The reference schedules' per-episode generator (docs/reference.md, "Schedule families"):
// default_rng(SeedSequence([base_seed, episode, worker]).generate_state(1, uint32)[0]).
// A schedule without a seed uses base_seed 0.
Random EpisodeRandom(uint64_t base_seed, uint64_t episode, uint64_t worker);

}  // namespace dcs

#endif  // DCS_COMMON_RANDOM_H_
