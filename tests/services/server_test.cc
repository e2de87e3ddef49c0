// Copyright 2026 The DCS Authors.
#include "services/server.h"

#include <memory>
#include <string>

#include "absl/status/status.h"
#include "absl/time/time.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/cluster_client.h"
#include "services/log.h"
#include "tests/testing/in_process_coordinator.h"

namespace dcs::services {
namespace {

using dcs::testing::InProcessCoordinator;
using ::testing::HasSubstr;
using cli::IsServing;

constexpr absl::Duration kRpcTimeout = absl::Seconds(10);
constexpr char kService[] = "dcs.v1.CoordinatorService";

// Each server under test serves a CoordinatorService: InProcessCoordinator::Start() is
// Server::Start() with one, and returns Server::Start()'s status unchanged.
class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Routes gRPC's own log messages through services/log.h, as every DCS main does.
    ConfigureLogging({.component = "test", .min_level = LogLevel::kError});
  }

  static absl::StatusOr<std::unique_ptr<InProcessCoordinator>> StartServer(
      const std::string& listen_address) {
    return InProcessCoordinator::Start({.listen_address = listen_address});
  }
};

TEST_F(ServerTest, BindsAFreePort) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> started = StartServer("127.0.0.1:0");
  ASSERT_TRUE(started.ok()) << started.status();
  EXPECT_GT((*started)->server().port(), 0);
  EXPECT_LT((*started)->server().port(), 65536);
}

TEST_F(ServerTest, HealthFollowsSetServing) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> started = StartServer("127.0.0.1:0");
  ASSERT_TRUE(started.ok()) << started.status();
  Server& server = (*started)->server();
  const std::string address = (*started)->address();

  for (const std::string service : {"", kService}) {
    absl::StatusOr<bool> serving = IsServing(address, service, kRpcTimeout);
    ASSERT_TRUE(serving.ok()) << serving.status();
    EXPECT_FALSE(*serving) << "'" << service << "' before SetServing(true)";
  }

  server.SetServing(true);
  for (const std::string service : {"", kService}) {
    absl::StatusOr<bool> serving = IsServing(address, service, kRpcTimeout);
    ASSERT_TRUE(serving.ok()) << serving.status();
    EXPECT_TRUE(*serving) << "'" << service << "' after SetServing(true)";
  }

  server.SetServing(false);
  for (const std::string service : {"", kService}) {
    absl::StatusOr<bool> serving = IsServing(address, service, kRpcTimeout);
    ASSERT_TRUE(serving.ok()) << serving.status();
    EXPECT_FALSE(*serving) << "'" << service << "' after SetServing(false)";
  }
}

TEST_F(ServerTest, UnknownServiceIsNotFound) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> started = StartServer("127.0.0.1:0");
  ASSERT_TRUE(started.ok()) << started.status();
  (*started)->server().SetServing(true);
  const absl::StatusOr<bool> serving =
      IsServing((*started)->address(), "dcs.v1.NoSuchService", kRpcTimeout);
  EXPECT_EQ(serving.status().code(), absl::StatusCode::kNotFound) << serving.status();
}

TEST_F(ServerTest, PortInUseIsUnavailableWithReason) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> first = StartServer("127.0.0.1:0");
  ASSERT_TRUE(first.ok()) << first.status();
  const std::string address = (*first)->address();

  const absl::StatusOr<std::unique_ptr<InProcessCoordinator>> second = StartServer(address);
  EXPECT_EQ(second.status().code(), absl::StatusCode::kUnavailable) << second.status();
  EXPECT_THAT(second.status().message(), HasSubstr(address));
  EXPECT_THAT(second.status().message(), HasSubstr("already in use"));

  // The first server is unaffected.
  (*first)->server().SetServing(true);
  const absl::StatusOr<bool> serving = IsServing(address, "", kRpcTimeout);
  ASSERT_TRUE(serving.ok()) << serving.status();
  EXPECT_TRUE(*serving);
}

TEST_F(ServerTest, UnparsableAddressIsUnavailable) {
  const absl::StatusOr<std::unique_ptr<InProcessCoordinator>> server =
      StartServer("not an address");
  EXPECT_EQ(server.status().code(), absl::StatusCode::kUnavailable) << server.status();
  EXPECT_THAT(server.status().message(), HasSubstr("not an address"));
}

TEST_F(ServerTest, ShutdownStopsServingAndIsIdempotent) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> started = StartServer("127.0.0.1:0");
  ASSERT_TRUE(started.ok()) << started.status();
  Server& server = (*started)->server();
  const std::string address = (*started)->address();
  server.SetServing(true);
  ASSERT_TRUE(IsServing(address, "", kRpcTimeout).value_or(false));

  server.Shutdown(absl::Milliseconds(100));
  server.Shutdown(absl::Milliseconds(100));
  server.SetServing(true);  // after shutdown: a no-op, must not crash

  const absl::StatusOr<bool> after = IsServing(address, "", absl::Seconds(1));
  EXPECT_FALSE(after.ok());
  EXPECT_THAT(after.status().code(), ::testing::AnyOf(absl::StatusCode::kUnavailable,
                                                      absl::StatusCode::kDeadlineExceeded));
}

TEST_F(ServerTest, PortIsFreeAgainAfterShutdown) {
  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> first = StartServer("127.0.0.1:0");
  ASSERT_TRUE(first.ok()) << first.status();
  const std::string address = (*first)->address();
  (*first)->server().Shutdown(absl::ZeroDuration());
  first->reset();

  absl::StatusOr<std::unique_ptr<InProcessCoordinator>> second = StartServer(address);
  ASSERT_TRUE(second.ok()) << second.status();
  (*second)->server().SetServing(true);
  EXPECT_TRUE(IsServing(address, kService, kRpcTimeout).value_or(false));
}

}  // namespace
}  // namespace dcs::services
