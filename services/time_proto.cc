// Copyright 2026 The DCS Authors.
#include "services/time_proto.h"

namespace dcs::services {

google::protobuf::Timestamp TimeToProto(absl::Time time) {
  const timespec ts = absl::ToTimespec(time);
  google::protobuf::Timestamp proto;
  proto.set_seconds(ts.tv_sec);
  proto.set_nanos(static_cast<int32_t>(ts.tv_nsec));
  return proto;
}

absl::Time TimeFromProto(const google::protobuf::Timestamp& proto) {
  return absl::FromUnixSeconds(proto.seconds()) + absl::Nanoseconds(proto.nanos());
}

google::protobuf::Duration DurationToProto(absl::Duration duration) {
  // Duration's nanos carry the sign of its seconds (unlike timespec's, which are >= 0).
  absl::Duration remainder;
  const int64_t seconds = absl::IDivDuration(duration, absl::Seconds(1), &remainder);
  google::protobuf::Duration proto;
  proto.set_seconds(seconds);
  proto.set_nanos(static_cast<int32_t>(absl::ToInt64Nanoseconds(remainder)));
  return proto;
}

absl::Duration DurationFromProto(const google::protobuf::Duration& proto) {
  return absl::Seconds(proto.seconds()) + absl::Nanoseconds(proto.nanos());
}

}  // namespace dcs::services
