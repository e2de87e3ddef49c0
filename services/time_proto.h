// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_TIME_PROTO_H_
#define DCS_SERVICES_TIME_PROTO_H_

// absl::Time and absl::Duration to and from google.protobuf.Timestamp and Duration.
// Thread-safe (pure functions).

#include <google/protobuf/duration.pb.h>
#include <google/protobuf/timestamp.pb.h>

#include "absl/time/time.h"

namespace dcs::services {

google::protobuf::Timestamp TimeToProto(absl::Time time);
absl::Time TimeFromProto(const google::protobuf::Timestamp& proto);
google::protobuf::Duration DurationToProto(absl::Duration duration);
absl::Duration DurationFromProto(const google::protobuf::Duration& proto);

}  // namespace dcs::services

#endif  // DCS_SERVICES_TIME_PROTO_H_
