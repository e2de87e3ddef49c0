// Copyright 2026 The DCS Authors.
#include "common/seed_sequence.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace dcs {
namespace {

// numpy's constants (bit_generator.pyx): INIT_A, MULT_A, INIT_B, MULT_B, MIX_MULT_L, MIX_MULT_R.
constexpr uint32_t kInitA = 0x43B0D7E5;
constexpr uint32_t kMultA = 0x931E8875;
constexpr uint32_t kInitB = 0x8B51F9DD;
constexpr uint32_t kMultB = 0x58F38DED;
constexpr uint32_t kMixMultL = 0xCA01F9DD;
constexpr uint32_t kMixMultR = 0x4973F715;
constexpr int kXShift = 16;  // 32-bit words: XSHIFT = 4 * 8 / 2

// numpy's hashmix: hashes `value` with the evolving constant `hash_const`.
inline uint32_t HashMix(uint32_t value, uint32_t& hash_const) {
  value ^= hash_const;
  hash_const *= kMultA;
  value *= hash_const;
  value ^= value >> kXShift;
  return value;
}

inline uint32_t Mix(uint32_t x, uint32_t y) {
  uint32_t result = kMixMultL * x - kMixMultR * y;
  result ^= result >> kXShift;
  return result;
}

// Calls `f(word)` for each entropy word of `values` in order: each value's little-endian 32-bit
// words, the value 0 giving one word 0 (numpy's _int_to_uint32_array).
template <typename F>
void ForEachWord(std::span<const uint64_t> values, F&& f) {
  for (uint64_t value : values) {
    do {
      f(static_cast<uint32_t>(value));
      value >>= 32;
    } while (value != 0);
  }
}

}  // namespace

SeedSequence::SeedSequence(std::span<const uint64_t> values) {
  // numpy's mix_entropy. The first kPoolSize words (0 where there are fewer) seed the pool, the
  // pool words are cross-mixed, then every further word is mixed into every pool word; the hash
  // constant evolves across all of it, so the words are visited in two passes in that order.
  std::array<uint32_t, kPoolSize> head = {0, 0, 0, 0};
  size_t num_words = 0;
  ForEachWord(values, [&](uint32_t word) {
    if (num_words < kPoolSize) head[num_words] = word;
    ++num_words;
  });
  uint32_t hash_const = kInitA;
  for (size_t i = 0; i < kPoolSize; ++i) pool_[i] = HashMix(head[i], hash_const);
  for (size_t src = 0; src < kPoolSize; ++src) {
    for (size_t dst = 0; dst < kPoolSize; ++dst) {
      if (src != dst) pool_[dst] = Mix(pool_[dst], HashMix(pool_[src], hash_const));
    }
  }
  if (num_words <= kPoolSize) return;
  size_t index = 0;
  ForEachWord(values, [&](uint32_t word) {
    if (index++ < kPoolSize) return;
    for (size_t dst = 0; dst < kPoolSize; ++dst) {
      pool_[dst] = Mix(pool_[dst], HashMix(word, hash_const));
    }
  });
}

void SeedSequence::GenerateState32(std::span<uint32_t> out) const {
  uint32_t hash_const = kInitB;
  for (size_t k = 0; k < out.size(); ++k) {
    uint32_t value = pool_[k % kPoolSize];
    value ^= hash_const;
    hash_const *= kMultB;
    value *= hash_const;
    value ^= value >> kXShift;
    out[k] = value;
  }
}

std::vector<uint32_t> SeedSequence::GenerateState32(size_t n) const {
  std::vector<uint32_t> out(n);
  GenerateState32(std::span<uint32_t>(out));
  return out;
}

std::vector<uint64_t> SeedSequence::GenerateState64(size_t n) const {
  const std::vector<uint32_t> words = GenerateState32(2 * n);
  std::vector<uint64_t> out(n);
  for (size_t j = 0; j < n; ++j) {
    out[j] = uint64_t{words[2 * j]} | uint64_t{words[2 * j + 1]} << 32;
  }
  return out;
}

}  // namespace dcs
