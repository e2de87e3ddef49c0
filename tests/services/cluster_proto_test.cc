// Copyright 2026 The DCS Authors.
#include "services/cluster_proto.h"

#include "absl/status/status.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

WorkerInfo SampleInfo(WorkerRole role) {
  return {.role = role,
          .address = "10.1.2.3:50052",
          .hostname = "gpu-node-7",
          .pid = 31337,
          .version = "0.1.0+3f2a9c1",
          .libraries = {{"libtorch", "1.13.1"}, {"box2d", "2.4.1"}}};
}

TEST(WorkerInfoProtoTest, ToProtoSetsEveryField) {
  const v1::WorkerInfo proto = WorkerInfoToProto(SampleInfo(WorkerRole::kLearner));
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
  for (const WorkerRole role : {WorkerRole::kLearner, WorkerRole::kActor}) {
    const WorkerInfo info = SampleInfo(role);
    const absl::StatusOr<WorkerInfo> back = WorkerInfoFromProto(WorkerInfoToProto(info));
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
  EXPECT_EQ(WorkerInfoToProto(SampleInfo(WorkerRole::kActor)).role(), v1::WORKER_ROLE_ACTOR);
}

TEST(WorkerInfoProtoTest, UnspecifiedRoleIsInvalidArgument) {
  v1::WorkerInfo proto = WorkerInfoToProto(SampleInfo(WorkerRole::kActor));
  proto.set_role(v1::WORKER_ROLE_UNSPECIFIED);
  const absl::StatusOr<WorkerInfo> info = WorkerInfoFromProto(proto);
  EXPECT_EQ(info.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(info.status().message(), HasSubstr("WORKER_ROLE_UNSPECIFIED"));
}

TEST(WorkerInfoProtoTest, UnknownRoleNumberIsInvalidArgument) {
  v1::WorkerInfo proto;
  proto.set_address("127.0.0.1:1");
  proto.set_role(static_cast<v1::WorkerRole>(17));  // an open enum keeps unknown values
  const absl::StatusOr<WorkerInfo> info = WorkerInfoFromProto(proto);
  EXPECT_EQ(info.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(info.status().message(), HasSubstr("17"));
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
