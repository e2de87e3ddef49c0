// Copyright 2026 The DCS Authors.
#include "common/seed_sequence.h"

#include <cstdint>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs {
namespace {

using ::testing::ElementsAre;

// Expected words below were printed by numpy 1.24.2 (Debian 12's python3-numpy), e.g.
// numpy.random.SeedSequence([1, 2, 3]).generate_state(6).

TEST(SeedSequenceTest, MatchesNumpyForAListOfInts) {
  const SeedSequence seed({1, 2, 3});
  EXPECT_THAT(seed.GenerateState32(6),
              ElementsAre(0xe3d1fc80, 0xb45f843f, 0x203807c7, 0x42c16e36, 0x0a344445, 0x10f7f367));
  EXPECT_THAT(seed.GenerateState64(3),
              ElementsAre(0xb45f843fe3d1fc80, 0x42c16e36203807c7, 0x10f7f3670a344445));
}

TEST(SeedSequenceTest, MatchesNumpyForSingleInts) {
  EXPECT_THAT(SeedSequence({0}).GenerateState32(4),
              ElementsAre(0xb0f478be, 0xdb2cd7e7, 0x2c71ba49, 0xabf4641a));
  EXPECT_THAT(
      SeedSequence({42}).GenerateState64(4),
      ElementsAre(0x9f1e2e6dcd540ab7, 0xd57873dc79fb94b6, 0x7d282a1b64d420b7, 0x336579714692d5ff));
}

TEST(SeedSequenceTest, SplitsValuesIntoLittleEndianWords) {
  // 2^32 is the words [0, 1]; 2^64 - 1 is [0xffffffff, 0xffffffff]; 2^40 + 7 is [7, 256].
  EXPECT_THAT(SeedSequence({uint64_t{1} << 32}).GenerateState32(2),
              ElementsAre(0xec53f444, 0x50ff846c));
  EXPECT_THAT(SeedSequence({UINT64_MAX}).GenerateState32(4),
              ElementsAre(0x928cad0d, 0xaebca151, 0x8638dc7a, 0x119c3044));
  EXPECT_THAT(SeedSequence({(uint64_t{1} << 40) + 7, 0, 9}).GenerateState32(4),
              ElementsAre(0x461f603d, 0x34f96911, 0x822e04a8, 0xe9a5b340));
}

TEST(SeedSequenceTest, MixesWordsBeyondThePool) {
  EXPECT_THAT(SeedSequence({1, 2, 3, 4, 5, 6}).GenerateState32(5),
              ElementsAre(0x1d1bca21, 0xebcd001d, 0xb202608b, 0xcfea83a4, 0xe4fcf5b6));
}

TEST(SeedSequenceTest, EmptyEntropyEqualsZero) {
  // numpy: SeedSequence([]) pads the pool with zero words, as SeedSequence(0) does.
  EXPECT_THAT(SeedSequence({}).GenerateState32(2), ElementsAre(0xb0f478be, 0xdb2cd7e7));
  EXPECT_EQ(SeedSequence({}), SeedSequence({0}));
}

TEST(SeedSequenceTest, SpanAndInitializerListAgree) {
  const std::vector<uint64_t> values = {5, uint64_t{1} << 33, 0, 17, 99};
  EXPECT_EQ(SeedSequence(values), SeedSequence({5, uint64_t{1} << 33, 0, 17, 99}));
  EXPECT_NE(SeedSequence(values), SeedSequence({5, uint64_t{1} << 33, 0, 17, 98}));
}

TEST(SeedSequenceTest, SpanOutputEqualsVectorOutput) {
  const SeedSequence seed({7, 8});
  std::vector<uint32_t> out(9);
  seed.GenerateState32(out);
  EXPECT_EQ(out, seed.GenerateState32(9));
  // A prefix of a longer state is the shorter state.
  EXPECT_EQ(seed.GenerateState32(1)[0], out[0]);
}

}  // namespace
}  // namespace dcs
