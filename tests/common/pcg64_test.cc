// Copyright 2026 The DCS Authors.
#include "common/pcg64.h"

#include <cstdint>
#include <random>

#include "common/seed_sequence.h"
#include "gtest/gtest.h"

namespace dcs {
namespace {

// Expected values: numpy 1.24.2 (Debian 12's
// python3-numpy): numpy.random.PCG64(seed).random_raw(n).

TEST(Pcg64Test, Seed42MatchesSpec) {
  Pcg64 bits(SeedSequence({42}));
  EXPECT_EQ(bits.Next64(), 0xc621fbcd16d92688);
  EXPECT_EQ(bits.Next64(), 0x705a5661a791ffc1);
  EXPECT_EQ(bits.Next64(), 0xdbcd12c26eda1624);
}

TEST(Pcg64Test, Seed0MatchesNumpy) {
  Pcg64 bits(SeedSequence({0}));
  EXPECT_EQ(bits.Next64(), 0xa30febcfd9c2825f);
  EXPECT_EQ(bits.Next64(), 0x4510bdf882d9d721);
  EXPECT_EQ(bits.Next64(), 0x0a7d3da94ecde8b8);
}

TEST(Pcg64Test, Next32ReturnsLowHalfThenSavedHighHalf) {
  // PCG64(7).random_raw(2) = 0xa00641a9f1e54a8b, 0xe5afcdbcaf266a95.
  Pcg64 bits(SeedSequence({7}));
  EXPECT_EQ(bits.Next32(), 0xf1e54a8bu);
  EXPECT_EQ(bits.Next32(), 0xa00641a9u);
  EXPECT_EQ(bits.Next32(), 0xaf266a95u);
  EXPECT_EQ(bits.Next32(), 0xe5afcdbcu);
}

TEST(Pcg64Test, SavedHalfSurvivesNext64) {
  Pcg64 bits(SeedSequence({7}));
  EXPECT_EQ(bits.Next32(), 0xf1e54a8bu);
  EXPECT_EQ(bits.Next64(), 0xe5afcdbcaf266a95);  // the second raw output, not the saved half
  EXPECT_EQ(bits.Next32(), 0xa00641a9u);         // the half saved before the Next64
}

TEST(Pcg64Test, CopyContinuesTheSameStream) {
  Pcg64 bits(SeedSequence({3}));
  bits.Next32();
  Pcg64 copy = bits;
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(bits.Next32(), copy.Next32());
    EXPECT_EQ(bits.Next64(), copy.Next64());
  }
}

TEST(Pcg64Test, IsAUniformRandomBitGenerator) {
  static_assert(std::uniform_random_bit_generator<Pcg64>);
  Pcg64 bits(SeedSequence({42}));
  EXPECT_EQ(bits(), 0xc621fbcd16d92688);
  std::uniform_int_distribution<int> dice(1, 6);
  const int roll = dice(bits);
  EXPECT_GE(roll, 1);
  EXPECT_LE(roll, 6);
}

}  // namespace
}  // namespace dcs
