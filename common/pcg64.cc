// Copyright 2026 The DCS Authors.
#include "common/pcg64.h"

#include <array>
#include <cstdint>

#include "common/seed_sequence.h"

namespace dcs {

Pcg64::Pcg64(const SeedSequence& seed) {
  // generate_state(4, uint64) without allocating: u[j] = words[2j] | words[2j + 1] << 32.
  std::array<uint32_t, 8> words;
  seed.GenerateState32(words);
  const auto u = [&words](int j) {
    return Uint128{uint64_t{words[2 * j]} | uint64_t{words[2 * j + 1]} << 32};
  };
  const Uint128 init_state = u(0) << 64 | u(1);
  const Uint128 init_sequence = u(2) << 64 | u(3);
  // pcg_setseq_128_srandom_r.
  increment_ = init_sequence << 1 | 1;
  state_ = 0;
  state_ = state_ * kMultiplier + increment_;
  state_ += init_state;
  state_ = state_ * kMultiplier + increment_;
}

}  // namespace dcs
