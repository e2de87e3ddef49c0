// Copyright 2026 The DCS Authors.
#ifndef DCS_COMMON_SEED_SEQUENCE_H_
#define DCS_COMMON_SEED_SEQUENCE_H_

// numpy's SeedSequence (numpy 1.24, `numpy/random/bit_generator.pyx`) for non-negative integer
// entropy: it hashes a list of integers into a 128-bit pool and expands the pool into as many
// well-mixed 32- or 64-bit words as a bit generator needs. Bit-exact with numpy, so seeds given to
// the reference implementation (Gymnasium, the reference schedules) give the same streams here.
// The algorithm is numpy's (numpy/random/bit_generator.pyx). Thread-safe: an immutable
// value type.

#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

namespace dcs {

class SeedSequence {
 public:
  // Entropy = each value split into little-endian 32-bit words (0 gives the one word 0, 2^32
  // gives the words 0, 1), concatenated in order: numpy's SeedSequence(5) is SeedSequence({5}),
  // SeedSequence([seed, episode, worker]) is SeedSequence({seed, episode, worker}). An empty list
  // is numpy's SeedSequence([]). (numpy's spawn keys are not modelled.)
  explicit SeedSequence(std::initializer_list<uint64_t> values)
      : SeedSequence(std::span<const uint64_t>(values.begin(), values.size())) {}
  explicit SeedSequence(std::span<const uint64_t> values);

  // numpy's generate_state(n, np.uint32): `n` words.
  std::vector<uint32_t> GenerateState32(size_t n) const;
  // The same words, written into `out` (no allocation): out[k] = generate_state(out.size())[k].
  void GenerateState32(std::span<uint32_t> out) const;
  // numpy's generate_state(n, np.uint64): word j is out32[2j] | out32[2j + 1] << 32 of the
  // 2n-word 32-bit state.
  std::vector<uint64_t> GenerateState64(size_t n) const;

  // Equal pools generate equal states (distinct entropies may, rarely, share a pool).
  friend bool operator==(const SeedSequence&, const SeedSequence&) = default;

 private:
  static constexpr size_t kPoolSize = 4;  // numpy's default pool_size, in 32-bit words

  std::array<uint32_t, kPoolSize> pool_;  // fixed at construction
};

}  // namespace dcs

#endif  // DCS_COMMON_SEED_SEQUENCE_H_
