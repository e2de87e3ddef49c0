// Copyright 2026 The DCS Authors.
#include "services/time_proto.h"

#include "absl/time/time.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

TEST(TimeProtoTest, TimeToProtoSplitsSecondsAndNanos) {
  const absl::Time time = absl::FromUnixSeconds(1'700'000'000) + absl::Nanoseconds(123'456'789);
  const google::protobuf::Timestamp proto = TimeToProto(time);
  EXPECT_EQ(proto.seconds(), 1'700'000'000);
  EXPECT_EQ(proto.nanos(), 123'456'789);
}

TEST(TimeProtoTest, TimesRoundTrip) {
  for (const absl::Time time :
       {absl::UnixEpoch(), absl::FromUnixSeconds(1'700'000'000),
        absl::FromUnixSeconds(1'700'000'000) + absl::Nanoseconds(1),
        absl::FromUnixSeconds(1'700'000'000) + absl::Milliseconds(999),
        absl::FromUnixNanos(1'763'717'400'987'654'321),
        // Before the epoch, with a fraction: nanos must still be non-negative.
        absl::FromUnixSeconds(-10) + absl::Milliseconds(250)}) {
    const google::protobuf::Timestamp proto = TimeToProto(time);
    EXPECT_GE(proto.nanos(), 0) << time;
    EXPECT_LT(proto.nanos(), 1'000'000'000) << time;
    EXPECT_EQ(TimeFromProto(proto), time) << time;
  }
}

TEST(TimeProtoTest, TimeFromProtoReadsFields) {
  google::protobuf::Timestamp proto;
  proto.set_seconds(42);
  proto.set_nanos(500'000'000);
  EXPECT_EQ(TimeFromProto(proto), absl::FromUnixMillis(42'500));
}

TEST(TimeProtoTest, DurationToProtoSplitsSecondsAndNanos) {
  const google::protobuf::Duration proto = DurationToProto(absl::Milliseconds(2'500));
  EXPECT_EQ(proto.seconds(), 2);
  EXPECT_EQ(proto.nanos(), 500'000'000);
}

TEST(TimeProtoTest, DurationsRoundTrip) {
  for (const absl::Duration duration :
       {absl::ZeroDuration(), absl::Nanoseconds(1), absl::Milliseconds(50), absl::Seconds(1),
        absl::Milliseconds(1'500), absl::Hours(30) + absl::Nanoseconds(7), absl::Seconds(-3)}) {
    EXPECT_EQ(DurationFromProto(DurationToProto(duration)), duration) << duration;
  }
}

// google.protobuf.Duration requires nanos to have the sign of seconds: -1.5s is {-1, -5e8}
// (not timespec's {-2, +5e8}, which protobuf's JSON printer rejects).
TEST(TimeProtoTest, NegativeDurationHasNanosWithTheSignOfSeconds) {
  const google::protobuf::Duration proto = DurationToProto(absl::Milliseconds(-1'500));
  EXPECT_EQ(proto.seconds(), -1);
  EXPECT_EQ(proto.nanos(), -500'000'000);
}

TEST(TimeProtoTest, DurationFromProtoReadsFields) {
  google::protobuf::Duration proto;
  proto.set_seconds(3);
  proto.set_nanos(250'000'000);
  EXPECT_EQ(DurationFromProto(proto), absl::Milliseconds(3'250));
}

TEST(TimeProtoTest, DurationFromProtoReadsNegativeDurations) {
  google::protobuf::Duration proto;
  proto.set_seconds(-1);
  proto.set_nanos(-500'000'000);
  EXPECT_EQ(DurationFromProto(proto), absl::Milliseconds(-1'500));
}

}  // namespace
}  // namespace dcs::services
