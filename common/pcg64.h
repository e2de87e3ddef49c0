// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_PCG64_H_
#define DCS_COMMON_PCG64_H_

// numpy's PCG64 bit generator (numpy 1.24, `numpy/random/src/pcg64/`): a 128-bit LCG with the
// XSL-RR 64-bit output, seeded from a SeedSequence exactly as numpy.random.PCG64(seed_seq) is, and
// numpy's buffered 32-bit output. Bit-exact with numpy (numpy/random/_pcg64.pyx).
// Thread-compatible; a value type (48 bytes), cheap to copy: a copy continues the same stream.

#include <cstdint>
#include <limits>

#include "common/seed_sequence.h"

namespace dcs {

class Pcg64 {
 public:
  using result_type = uint64_t;  // a UniformRandomBitGenerator: usable with <random>

  // State from seed.generate_state(4, uint64) = u: initstate = u[0]·2^64 + u[1],
  // initseq = u[2]·2^64 + u[3] (numpy's pcg64_set_seed); no saved 32-bit half.
  explicit Pcg64(const SeedSequence& seed);

  // The next 64-bit output (numpy's next_uint64 / random_raw()). Leaves a saved 32-bit half alone.
  uint64_t Next64() {
    state_ = state_ * kMultiplier + increment_;
    const uint64_t hi = static_cast<uint64_t>(state_ >> 64);
    const uint64_t lo = static_cast<uint64_t>(state_);
    const unsigned rotation = static_cast<unsigned>(hi >> 58);
    const uint64_t x = hi ^ lo;
    return (x >> rotation) | (x << ((64 - rotation) & 63));
  }

  // numpy's next_uint32: returns the saved upper half of an earlier Next64 draw if there is one
  // (and forgets it); otherwise draws n = Next64(), saves n >> 32 and returns the low 32 bits.
  // The saved half survives intervening Next64 calls (numpy's random() and uniform() keep it).
  uint32_t Next32() {
    if (has_saved_half_) {
      has_saved_half_ = false;
      return saved_half_;
    }
    const uint64_t next = Next64();
    saved_half_ = static_cast<uint32_t>(next >> 32);
    has_saved_half_ = true;
    return static_cast<uint32_t>(next);
  }

  static constexpr uint64_t min() { return 0; }
  static constexpr uint64_t max() { return std::numeric_limits<uint64_t>::max(); }
  uint64_t operator()() { return Next64(); }

 private:
  __extension__ typedef unsigned __int128 Uint128;  // __extension__: no -Wpedantic warning

  // numpy's PCG_DEFAULT_MULTIPLIER_128 = 0x2360ED051FC65DA44385DF649FCCF645.
  static constexpr Uint128 kMultiplier =
      (Uint128{0x2360ED051FC65DA4ULL} << 64) | Uint128{0x4385DF649FCCF645ULL};

  Uint128 state_;
  Uint128 increment_;  // odd; fixed at construction
  uint32_t saved_half_ = 0;
  bool has_saved_half_ = false;
};

}  // namespace dcs

#endif  // DCS_COMMON_PCG64_H_
