// Copyright 2026 The DCS Authors.
#include "services/cluster_proto.h"

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

coordinator::WorkerInfo SampleInfo(coordinator::WorkerRole role) {
  return {.role = role,
          .address = "10.1.2.3:50052",
          .hostname = "gpu-node-7",
          .pid = 31337,
          .version = "0.1.0+3f2a9c1",
          .libraries = {{"libtorch", "1.13.1"}, {"box2d", "2.4.1"}}};
}

TEST(WorkerInfoProtoTest, ToProtoSetsEveryField) {
  const v1::WorkerInfo proto = WorkerInfoToProto(SampleInfo(coordinator::WorkerRole::kLearner));
  EXPECT_EQ(proto.role(), v1::WORKER_ROLE_LEARNER);
  EXPECT_EQ(proto.address(), "10.1.2.3:50052");
  EXPECT_EQ(proto.hostname(), "gpu-node-7");
  EXPECT_EQ(proto.pid(), 31337);
  EXPECT_EQ(proto.build().version(), "0.1.0+3f2a9c1");
  ASSERT_EQ(proto.build().libraries_size(), 2);
  EXPECT_EQ(proto.build().libraries(0).name(), "libtorch");
  EXPECT_EQ(proto.build().libraries(0).version(), "1.13.1");
  EXPECT_EQ(proto.build().libraries(1).name(), "box2d");
  EXPECT_EQ(proto.build().libraries(1).version(), "2.4.1");
}

TEST(WorkerInfoProtoTest, RoundTripsBothRoles) {
  for (const coordinator::WorkerRole role :
       {coordinator::WorkerRole::kLearner, coordinator::WorkerRole::kActor}) {
    const coordinator::WorkerInfo info = SampleInfo(role);
    const absl::StatusOr<coordinator::WorkerInfo> back =
        WorkerInfoFromProto(WorkerInfoToProto(info));
    ASSERT_TRUE(back.ok()) << back.status();
    EXPECT_EQ(back->role, info.role);
    EXPECT_EQ(back->address, info.address);
    EXPECT_EQ(back->hostname, info.hostname);
    EXPECT_EQ(back->pid, info.pid);
    EXPECT_EQ(back->version, info.version);
    EXPECT_THAT(back->libraries, ElementsAre(LibraryVersion{"libtorch", "1.13.1"},
                                             LibraryVersion{"box2d", "2.4.1"}));
  }
}

TEST(WorkerInfoProtoTest, ActorRoleMapsToActor) {
  EXPECT_EQ(WorkerInfoToProto(SampleInfo(coordinator::WorkerRole::kActor)).role(),
            v1::WORKER_ROLE_ACTOR);
}

TEST(WorkerInfoProtoTest, UnspecifiedRoleIsInvalidArgument) {
  v1::WorkerInfo proto = WorkerInfoToProto(SampleInfo(coordinator::WorkerRole::kActor));
  proto.set_role(v1::WORKER_ROLE_UNSPECIFIED);
  const absl::StatusOr<coordinator::WorkerInfo> info = WorkerInfoFromProto(proto);
  EXPECT_EQ(info.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(info.status().message(), HasSubstr("WORKER_ROLE_UNSPECIFIED"));
}

TEST(WorkerInfoProtoTest, UnknownRoleNumberIsInvalidArgument) {
  v1::WorkerInfo proto;
  proto.set_address("127.0.0.1:1");
  proto.set_role(static_cast<v1::WorkerRole>(17));  // an open enum keeps unknown values
  const absl::StatusOr<coordinator::WorkerInfo> info = WorkerInfoFromProto(proto);
  EXPECT_EQ(info.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(info.status().message(), HasSubstr("17"));
}

TEST(WorkerProtoTest, CarriesIdStateAndTimes) {
  const absl::Time registered = absl::FromUnixMillis(1'763'717'400'123);
  const absl::Time heartbeat = registered + absl::Milliseconds(4'567);
  coordinator::WorkerRecord record{.id = "learner-3",
                                   .info = SampleInfo(coordinator::WorkerRole::kLearner),
                                   .state = coordinator::WorkerState::kLost,
                                   .registered_at = registered,
                                   .last_heartbeat_at = heartbeat};
  v1::Worker proto = WorkerToProto(record);
  EXPECT_EQ(proto.worker_id(), "learner-3");
  EXPECT_EQ(proto.state(), v1::WORKER_STATE_LOST);
  EXPECT_EQ(TimeFromProto(proto.registered_time()), registered);
  EXPECT_EQ(TimeFromProto(proto.last_heartbeat_time()), heartbeat);
  EXPECT_EQ(proto.info().role(), v1::WORKER_ROLE_LEARNER);
  EXPECT_EQ(proto.info().address(), "10.1.2.3:50052");
  EXPECT_EQ(proto.info().build().libraries_size(), 2);

  record.state = coordinator::WorkerState::kAlive;
  EXPECT_EQ(WorkerToProto(record).state(), v1::WORKER_STATE_ALIVE);
}

TEST(BuildInfoProtoTest, CarriesVersionAndLibrariesInOrder) {
  const v1::BuildInfo proto =
      BuildInfoToProto({.version = "1.2.3+abc", .libraries = {{"grpc", "1.51.1"}, {"x", "2"}}});
  EXPECT_EQ(proto.version(), "1.2.3+abc");
  ASSERT_EQ(proto.libraries_size(), 2);
  EXPECT_EQ(proto.libraries(0).name(), "grpc");
  EXPECT_EQ(proto.libraries(0).version(), "1.51.1");
  EXPECT_EQ(proto.libraries(1).name(), "x");
  EXPECT_EQ(proto.libraries(1).version(), "2");
}

}  // namespace
}  // namespace dcs::services
