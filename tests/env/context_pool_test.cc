// Copyright 2026 The DCS Authors.
//
// Context pools (docs/reference.md, "Pools"): construction by size (midpoint insertion / linspace)
// and by explicit values, and the selection of an episode's initial value.

#include "env/context_pool.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

#include "absl/status/statusor.h"
#include "common/random.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::env {
namespace {

using ::testing::AllOf;
using ::testing::DoubleNear;
using ::testing::ElementsAre;
using ::testing::Ge;
using ::testing::HasSubstr;
using ::testing::Le;
using ::testing::Pointwise;

std::vector<double> PoolOfSize(double lo, double hi, int size) {
  absl::StatusOr<ContextPool> pool = ContextPool::OfSize(lo, hi, size);
  EXPECT_TRUE(pool.ok()) << pool.status();
  return pool.ok() ? pool->values() : std::vector<double>{};
}

std::vector<double> Linspace(double lo, double hi, int n) {
  std::vector<double> values;
  for (int i = 0; i < n; ++i) values.push_back(lo + (hi - lo) * i / (n - 1));
  return values;
}

TEST(ContextPoolTest, PoolOneIsTheMidpoint) {
  EXPECT_THAT(PoolOfSize(0.35, 0.75, 1), ElementsAre(DoubleNear(0.55, 1e-15)));
  EXPECT_THAT(PoolOfSize(-0.6, 0.6, 1), ElementsAre(DoubleNear(0.0, 1e-15)));
}

TEST(ContextPoolTest, PoolThreeAddsTheExtremes) {
  EXPECT_THAT(PoolOfSize(0.35, 0.75, 3),
              ElementsAre(0.35, DoubleNear(0.55, 1e-15), 0.75));
  EXPECT_THAT(PoolOfSize(-0.6, 0.6, 3), ElementsAre(-0.6, DoubleNear(0.0, 1e-15), 0.6));
}

TEST(ContextPoolTest, PoolFiveAndNineInsertMidpoints) {
  // The paper's force-magnitude pool-5.
  EXPECT_THAT(PoolOfSize(5, 15, 5), ElementsAre(5.0, 7.5, 10.0, 12.5, 15.0));
  EXPECT_THAT(PoolOfSize(0, 8, 9), ElementsAre(0, 1, 2, 3, 4, 5, 6, 7, 8));
}

TEST(ContextPoolTest, OtherSizesAreLinspace) {
  EXPECT_THAT(PoolOfSize(0.35, 0.75, 7),
              Pointwise(DoubleNear(1e-12), Linspace(0.35, 0.75, 7)));
  EXPECT_THAT(PoolOfSize(-0.6, 0.6, 7), Pointwise(DoubleNear(1e-12),
                                                 {-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6}));
  EXPECT_THAT(PoolOfSize(0, 14, 15), Pointwise(DoubleNear(1e-12), Linspace(0, 14, 15)));
  EXPECT_THAT(PoolOfSize(1, 2, 2), ElementsAre(1.0, 2.0));
  // Pool-7 over the CartPole training range is NOT midpoint insertion's 0.45 and 0.65.
  const std::vector<double> pool7 = PoolOfSize(0.35, 0.75, 7);
  EXPECT_NEAR(pool7[1], 0.4166666666666667, 1e-12);
}

TEST(ContextPoolTest, MidpointInsertionEqualsLinspaceWhereBothExist) {
  for (int levels = 1; levels <= 6; ++levels) {
    const int size = (1 << levels) + 1;
    SCOPED_TRACE(size);
    const std::vector<double> inserted = MidpointInsertion(0.35, 0.75, levels);
    ASSERT_EQ(inserted.size(), static_cast<size_t>(size));
    EXPECT_THAT(inserted, Pointwise(DoubleNear(1e-12), Linspace(0.35, 0.75, size)));
    EXPECT_THAT(PoolOfSize(0.35, 0.75, size), Pointwise(DoubleNear(1e-12), inserted));
  }
  EXPECT_THAT(MidpointInsertion(2, 4, 0), ElementsAre(3.0));
  EXPECT_THAT(MidpointInsertion(2, 4, 1), ElementsAre(2.0, 3.0, 4.0));
  EXPECT_THAT(MidpointInsertion(0, 1, 2), ElementsAre(0.0, 0.25, 0.5, 0.75, 1.0));
}

TEST(ContextPoolTest, SizesAreAscendingAndKeepTheRange) {
  for (int size : {2, 3, 4, 5, 6, 7, 15, 31, 61}) {
    SCOPED_TRACE(size);
    const std::vector<double> values = PoolOfSize(-1.5, 2.5, size);
    ASSERT_EQ(values.size(), static_cast<size_t>(size));
    EXPECT_DOUBLE_EQ(values.front(), -1.5);
    EXPECT_DOUBLE_EQ(values.back(), 2.5);
    for (size_t i = 1; i < values.size(); ++i) EXPECT_LT(values[i - 1], values[i]);
  }
}

TEST(ContextPoolTest, PapersCartPolePoolSevenAsExplicitValues) {
  const std::vector<double> paper = {0.35, 0.41, 0.48, 0.55, 0.62, 0.68, 0.75};
  absl::StatusOr<ContextPool> pool = ContextPool::OfValues(paper);
  ASSERT_TRUE(pool.ok()) << pool.status();
  EXPECT_EQ(pool->values(), paper);  // verbatim, in the given order
  absl::StatusOr<ContextPool> unordered = ContextPool::OfValues({0.7, 0.1, 0.7});
  ASSERT_TRUE(unordered.ok());
  EXPECT_THAT(unordered->values(), ElementsAre(0.7, 0.1, 0.7));
}

TEST(ContextPoolTest, Errors) {
  EXPECT_THAT(ContextPool::OfSize(1, 0, 3).status().message(), HasSubstr("lo <= hi"));
  EXPECT_FALSE(ContextPool::OfSize(0, std::numeric_limits<double>::infinity(), 3).ok());
  EXPECT_FALSE(ContextPool::OfSize(std::numeric_limits<double>::quiet_NaN(), 1, 3).ok());
  EXPECT_THAT(ContextPool::OfSize(0, 1, 0).status().message(), HasSubstr("size"));
  EXPECT_FALSE(ContextPool::OfSize(0, 1, -1).ok());
  EXPECT_FALSE(ContextPool::OfSize(0, 1, 10001).ok());
  EXPECT_TRUE(ContextPool::OfSize(0, 1, 10000).ok());
  // lo == hi is a degenerate but valid range.
  EXPECT_THAT(PoolOfSize(0.5, 0.5, 3), ElementsAre(0.5, 0.5, 0.5));
  EXPECT_FALSE(ContextPool::OfValues({}).ok());
  EXPECT_FALSE(ContextPool::OfValues({0.1, std::numeric_limits<double>::quiet_NaN()}).ok());
  EXPECT_FALSE(ContextPool::OfValues({std::numeric_limits<double>::infinity()}).ok());
}

TEST(ContextPoolTest, RoundRobinRotatesBySlot) {
  absl::StatusOr<ContextPool> pool = ContextPool::OfValues({10, 20, 30});
  ASSERT_TRUE(pool.ok());
  Random random(uint64_t{1});
  const Random untouched = random;
  std::vector<double> slot0;
  std::vector<double> slot1;
  std::vector<double> slot5;
  for (uint64_t episode = 0; episode < 6; ++episode) {
    slot0.push_back(pool->Select(ContextPool::Selection::kRoundRobin, episode, 0, random));
    slot1.push_back(pool->Select(ContextPool::Selection::kRoundRobin, episode, 1, random));
    slot5.push_back(pool->Select(ContextPool::Selection::kRoundRobin, episode, 5, random));
  }
  EXPECT_THAT(slot0, ElementsAre(10, 20, 30, 10, 20, 30));
  EXPECT_THAT(slot1, ElementsAre(20, 30, 10, 20, 30, 10));  // rotated left by 1
  EXPECT_THAT(slot5, ElementsAre(30, 10, 20, 30, 10, 20));  // by 5 mod 3 = 2
  // Round robin does not use the random stream.
  Random copy = untouched;
  EXPECT_EQ(random.Uniform01(), copy.Uniform01());
}

TEST(ContextPoolTest, RandomSelectionIsUniformOverTheValues) {
  // 70000 draws over 7 values: each count is Binomial(70000, 1/7), mean 10000, sd 92.6;
  // accept +- 463 (5 sd).
  absl::StatusOr<ContextPool> pool = ContextPool::OfSize(0.35, 0.75, 7);
  ASSERT_TRUE(pool.ok());
  Random random(uint64_t{77});
  std::map<double, int> counts;
  for (uint64_t episode = 0; episode < 70000; ++episode) {
    ++counts[pool->Select(ContextPool::Selection::kRandom, episode, 0, random)];
  }
  ASSERT_EQ(counts.size(), 7u);
  for (const auto& [value, count] : counts) {
    EXPECT_THAT(count, AllOf(Ge(9537), Le(10463))) << value;
  }
}

TEST(ContextPoolTest, RandomSelectionIsDeterministicGivenTheRandom) {
  absl::StatusOr<ContextPool> pool = ContextPool::OfSize(0, 1, 15);
  ASSERT_TRUE(pool.ok());
  Random a(uint64_t{5});
  Random b(uint64_t{5});
  Random c(uint64_t{6});
  std::vector<double> va;
  std::vector<double> vb;
  std::vector<double> vc;
  for (uint64_t episode = 0; episode < 50; ++episode) {
    va.push_back(pool->Select(ContextPool::Selection::kRandom, episode, 0, a));
    vb.push_back(pool->Select(ContextPool::Selection::kRandom, episode, 0, b));
    vc.push_back(pool->Select(ContextPool::Selection::kRandom, episode, 0, c));
  }
  EXPECT_EQ(va, vb);
  EXPECT_NE(va, vc);
  // A single-value pool always gives its value.
  absl::StatusOr<ContextPool> single = ContextPool::OfValues({0.55});
  ASSERT_TRUE(single.ok());
  for (uint64_t episode = 0; episode < 5; ++episode) {
    EXPECT_EQ(single->Select(ContextPool::Selection::kRandom, episode, 3, a), 0.55);
    EXPECT_EQ(single->Select(ContextPool::Selection::kRoundRobin, episode, 3, a), 0.55);
  }
}

}  // namespace
}  // namespace dcs::env
