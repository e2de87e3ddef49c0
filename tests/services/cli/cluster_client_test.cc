// Copyright 2026 The DCS Authors.
#include "services/cli/cluster_client.h"

#include <memory>
#include <string>

#include "absl/status/status.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/build_info.h"
#include "services/log.h"
#include "tests/testing/in_process_coordinator.h"
#include "tests/testing/net.h"

namespace dcs::services::cli {
namespace {

using dcs::testing::InProcessCoordinator;
using dcs::testing::RefusingPort;
using ::testing::AnyOf;
using ::testing::HasSubstr;

constexpr absl::Duration kRpcTimeout = absl::Seconds(10);

class ClusterClientTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ConfigureLogging({.component = "test", .min_level = LogLevel::kError});
    absl::StatusOr<std::unique_ptr<InProcessCoordinator>> coordinator =
        InProcessCoordinator::Start();
    ASSERT_TRUE(coordinator.ok()) << coordinator.status();
    coordinator_ = *std::move(coordinator);
    address_ = coordinator_->address();
  }

  std::unique_ptr<InProcessCoordinator> coordinator_;
  std::string address_;
};

TEST_F(ClusterClientTest, IsServingReportsHealth) {
  absl::StatusOr<bool> serving = IsServing(address_, "", kRpcTimeout);
  ASSERT_TRUE(serving.ok()) << serving.status();
  EXPECT_FALSE(*serving);
  coordinator_->server().SetServing(true);
  serving = IsServing(address_, "", kRpcTimeout);
  ASSERT_TRUE(serving.ok()) << serving.status();
  EXPECT_TRUE(*serving);
}

TEST_F(ClusterClientTest, IsServingUnknownServiceIsNotFoundNamingTheAddress) {
  const absl::StatusOr<bool> serving = IsServing(address_, "no.such.Service", kRpcTimeout);
  EXPECT_EQ(serving.status().code(), absl::StatusCode::kNotFound);
  EXPECT_THAT(serving.status().message(), HasSubstr(address_));
}

TEST_F(ClusterClientTest, IsServingUnreachableIsUnavailable) {
  RefusingPort refusing;
  ASSERT_GT(refusing.port(), 0);
  const absl::StatusOr<bool> serving = IsServing(refusing.address(), "", kRpcTimeout);
  EXPECT_THAT(serving.status().code(),
              AnyOf(absl::StatusCode::kUnavailable, absl::StatusCode::kDeadlineExceeded));
  EXPECT_THAT(serving.status().message(), HasSubstr(refusing.address()));
}

TEST_F(ClusterClientTest, WaitUntilServingReturnsOnceServing) {
  coordinator_->server().SetServing(true);
  const absl::Status status = WaitUntilServing(address_, "dcs.v1.CoordinatorService", kRpcTimeout);
  EXPECT_TRUE(status.ok()) << status;
}

TEST_F(ClusterClientTest, WaitUntilServingTimesOutWithLastAnswer) {
  const absl::Status status =
      WaitUntilServing(address_, "dcs.v1.CoordinatorService", absl::Milliseconds(300));
  EXPECT_EQ(status.code(), absl::StatusCode::kDeadlineExceeded);
  EXPECT_THAT(status.message(), HasSubstr(address_));
  EXPECT_THAT(status.message(), HasSubstr("NOT_SERVING"));
}

TEST_F(ClusterClientTest, GetClusterStatusReturnsWorkers) {
  WorkerInfo info{.role = WorkerRole::kLearner, .address = "h:1"};
  const absl::StatusOr<std::string> id = coordinator_->registry().Register(info, absl::Now());
  ASSERT_TRUE(id.ok()) << id.status();
  const absl::StatusOr<v1::GetClusterStatusResponse> status =
      GetClusterStatus(address_, kRpcTimeout);
  ASSERT_TRUE(status.ok()) << status.status();
  ASSERT_EQ(status->workers_size(), 1);
  EXPECT_EQ(status->workers(0).worker_id(), *id);
  EXPECT_EQ(status->workers(0).info().address(), "h:1");
  EXPECT_EQ(status->coordinator_build().version(), DcsVersion());
}

TEST_F(ClusterClientTest, GetClusterStatusUnreachableNamesTheCoordinator) {
  RefusingPort refusing;
  ASSERT_GT(refusing.port(), 0);
  const absl::StatusOr<v1::GetClusterStatusResponse> status =
      GetClusterStatus(refusing.address(), kRpcTimeout);
  EXPECT_THAT(status.status().code(),
              AnyOf(absl::StatusCode::kUnavailable, absl::StatusCode::kDeadlineExceeded));
  EXPECT_THAT(status.status().message(), HasSubstr("coordinator " + refusing.address()));
}

}  // namespace
}  // namespace dcs::services::cli
