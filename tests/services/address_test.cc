// Copyright 2026 The DCS Authors.
#include "services/address.h"

#include "gtest/gtest.h"

namespace dcs::services {
namespace {

TEST(AddressTest, HostOfAndWithPortKeepIpv6Brackets) {
  EXPECT_EQ(HostOf("127.0.0.1:50051"), "127.0.0.1");
  EXPECT_EQ(HostOf("[::1]:0"), "[::1]");
  EXPECT_EQ(WithPort("[::1]:0", 41234), "[::1]:41234");
  EXPECT_EQ(WithPort("coordinator:50051", 9), "coordinator:9");
}

TEST(AddressTest, JoinHostPortBracketsABareIpv6Host) {
  EXPECT_EQ(JoinHostPort("fd00::1", 50052), "[fd00::1]:50052");
  EXPECT_EQ(JoinHostPort("[fd00::1]", 50052), "[fd00::1]:50052");
  EXPECT_EQ(JoinHostPort("10.0.0.7", 50052), "10.0.0.7:50052");
  EXPECT_EQ(JoinHostPort("learner-0", 50052), "learner-0:50052");
}

}  // namespace
}  // namespace dcs::services
