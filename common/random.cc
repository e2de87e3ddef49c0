// Copyright 2026 The DCS Authors.
#include "common/random.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <vector>

#include "absl/strings/string_view.h"
#include "common/seed_sequence.h"

namespace dcs {

uint64_t Random::Lemire32Reject(uint64_t m, uint32_t max_offset) {
  const uint32_t range = max_offset + 1;  // max_offset < 2^32 - 1: no overflow
  // Products whose low word is below (2^32 - range) mod range would bias the result.
  const uint32_t threshold = (UINT32_MAX - max_offset) % range;
  while (static_cast<uint32_t>(m) < threshold) m = uint64_t{bits_.Next32()} * range;
  return m;
}

uint64_t Random::WideOffset(uint64_t max_offset) {
  // numpy's random_bounded_uint64_fill beyond the 32-bit Lemire path. max_offset < 2^64 - 1
  // because lo < hi, so numpy's full-range branch (a bare next_uint64) cannot occur.
  if (max_offset == 0xFFFFFFFF) return bits_.Next32();
  __extension__ typedef unsigned __int128 Uint128;
  const uint64_t range = max_offset + 1;
  Uint128 m = Uint128{bits_.Next64()} * range;
  if (static_cast<uint64_t>(m) < range) {
    const uint64_t threshold = (UINT64_MAX - max_offset) % range;
    while (static_cast<uint64_t>(m) < threshold) m = Uint128{bits_.Next64()} * range;
  }
  return static_cast<uint64_t>(m >> 64);
}

double Random::StandardNormalPair() {
  double u;
  double v;
  double s;
  do {
    u = 2.0 * Uniform01() - 1.0;
    v = 2.0 * Uniform01() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double factor = std::sqrt(-2.0 * std::log(s) / s);
  spare_normal_ = v * factor;
  has_spare_normal_ = true;
  return u * factor;
}

uint64_t Fnv1a64(absl::string_view name) {
  uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : name) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

SeedSequence StreamSeed(uint64_t seed, absl::string_view name,
                        std::initializer_list<uint64_t> indices) {
  const size_t size = 2 + indices.size();
  const auto fill = [&](std::span<uint64_t> values) {
    values[0] = seed;
    values[1] = Fnv1a64(name);
    size_t i = 2;
    for (const uint64_t index : indices) values[i++] = index;
    return SeedSequence(std::span<const uint64_t>(values));
  };
  constexpr size_t kInline = 8;  // no allocation for up to six indices
  if (size <= kInline) {
    std::array<uint64_t, kInline> values;
    return fill(std::span<uint64_t>(values.data(), size));
  }
  std::vector<uint64_t> values(size);
  return fill(values);
}

Random EpisodeRandom(uint64_t base_seed, uint64_t episode, uint64_t worker) {
  std::array<uint32_t, 1> episode_seed;
  SeedSequence({base_seed, episode, worker}).GenerateState32(episode_seed);
  return Random(uint64_t{episode_seed[0]});
}

}  // namespace dcs
