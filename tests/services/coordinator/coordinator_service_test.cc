// Copyright 2026 The DCS Authors.
#include "services/coordinator/coordinator_service.h"

#include <memory>
#include <string>
#include <vector>

#include <grpcpp/grpcpp.h>
#include <prometheus/metric_family.h>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/build_info.h"
#include "services/channel.h"
#include "services/log.h"
#include "services/metrics_endpoint.h"
#include "services/time_proto.h"
#include "tests/testing/in_process_coordinator.h"
#include "tests/testing/net.h"

namespace dcs::services {
namespace {

using dcs::testing::HttpGet;
using dcs::testing::InProcessCoordinator;
using ::testing::ContainsRegex;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr absl::Duration kRpcTimeout = absl::Seconds(10);

// A coordinator served in this process on a free loopback port.
class CoordinatorServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ConfigureLogging({.component = "test", .min_level = LogLevel::kError});
    start_time_ = absl::Now() - absl::Seconds(30);
    build_ = ProcessBuildInfo({{"sqlite", "3.40.1"}});
    absl::StatusOr<std::unique_ptr<InProcessCoordinator>> coordinator =
        InProcessCoordinator::Start({.registry = {.heartbeat_interval = absl::Milliseconds(1500),
                                                  .lost_after = absl::Seconds(5),
                                                  .forget_after = absl::Minutes(1)},
                                     .build = build_,
                                     .start_time = start_time_,
                                     .serving = true});
    ASSERT_TRUE(coordinator.ok()) << coordinator.status();
    coordinator_ = *std::move(coordinator);
    stub_ = v1::CoordinatorService::NewStub(OpenChannel(coordinator_->address()));
  }

  void TearDown() override {
    stub_.reset();
    coordinator_.reset();
  }

  coordinator::WorkerRegistry& registry() { return coordinator_->registry(); }

  static v1::WorkerInfo Worker(v1::WorkerRole role, const std::string& address) {
    v1::WorkerInfo worker;
    worker.set_role(role);
    worker.set_address(address);
    worker.set_hostname("node-1");
    worker.set_pid(777);
    worker.mutable_build()->set_version("0.1.0+w0rk3r");
    auto* library = worker.mutable_build()->add_libraries();
    library->set_name("libtorch");
    library->set_version("1.13.1");
    return worker;
  }

  grpc::Status Register(const v1::WorkerInfo& worker, v1::RegisterWorkerResponse* response) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    v1::RegisterWorkerRequest request;
    *request.mutable_worker() = worker;
    return stub_->RegisterWorker(&context, request, response);
  }

  grpc::Status Heartbeat(const std::string& id) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    v1::HeartbeatRequest request;
    request.set_worker_id(id);
    v1::HeartbeatResponse response;
    return stub_->Heartbeat(&context, request, &response);
  }

  grpc::Status Unregister(const std::string& id) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    v1::UnregisterWorkerRequest request;
    request.set_worker_id(id);
    v1::UnregisterWorkerResponse response;
    return stub_->UnregisterWorker(&context, request, &response);
  }

  grpc::Status Status(v1::GetClusterStatusResponse* response) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    return stub_->GetClusterStatus(&context, {}, response);
  }

  // The value of a counter series with exactly `labels` among its labels; -1 if absent.
  double CounterValue(const std::string& family_name,
                      const std::vector<std::pair<std::string, std::string>>& labels) {
    for (const prometheus::MetricFamily& family : coordinator_->metrics()->Collect()) {
      if (family.name != family_name) continue;
      for (const prometheus::ClientMetric& metric : family.metric) {
        int matched = 0;
        for (const auto& [name, value] : labels) {
          for (const prometheus::ClientMetric::Label& label : metric.label) {
            if (label.name == name && label.value == value) ++matched;
          }
        }
        if (matched == static_cast<int>(labels.size())) return metric.counter.value;
      }
    }
    return -1;
  }

  BuildInfo build_;
  absl::Time start_time_;
  std::unique_ptr<InProcessCoordinator> coordinator_;
  std::unique_ptr<v1::CoordinatorService::Stub> stub_;
};

TEST_F(CoordinatorServiceTest, RegisterReturnsIdAndHeartbeatInterval) {
  v1::RegisterWorkerResponse response;
  const grpc::Status status = Register(Worker(v1::WORKER_ROLE_ACTOR, "10.0.0.9:7000"), &response);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_THAT(response.worker_id(), StartsWith("actor-"));
  EXPECT_EQ(DurationFromProto(response.heartbeat_interval()), absl::Milliseconds(1500));

  const std::vector<coordinator::WorkerRecord> records = registry().List(absl::Now());
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].id, response.worker_id());
  EXPECT_EQ(records[0].info.address, "10.0.0.9:7000");
  EXPECT_EQ(records[0].info.pid, 777);
  EXPECT_EQ(records[0].info.version, "0.1.0+w0rk3r");
  ASSERT_EQ(records[0].info.libraries.size(), 1u);
  EXPECT_EQ(records[0].info.libraries[0].name, "libtorch");
}

TEST_F(CoordinatorServiceTest, RegisterCountsByRole) {
  v1::RegisterWorkerResponse response;
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_LEARNER, "h:1"), &response).ok());
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "h:2"), &response).ok());
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "h:3"), &response).ok());
  EXPECT_EQ(CounterValue("dcs_worker_registrations_total", {{"role", "learner"}}), 1);
  EXPECT_EQ(CounterValue("dcs_worker_registrations_total", {{"role", "actor"}}), 2);
}

TEST_F(CoordinatorServiceTest, UnspecifiedRoleIsInvalidArgument) {
  v1::RegisterWorkerResponse response;
  const grpc::Status status =
      Register(Worker(v1::WORKER_ROLE_UNSPECIFIED, "10.0.0.9:7000"), &response);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_THAT(status.error_message(), HasSubstr("role"));
  EXPECT_TRUE(registry().List(absl::Now()).empty());
}

TEST_F(CoordinatorServiceTest, EmptyAddressIsInvalidArgument) {
  v1::RegisterWorkerResponse response;
  EXPECT_EQ(Register(Worker(v1::WORKER_ROLE_ACTOR, ""), &response).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_TRUE(registry().List(absl::Now()).empty());
}

TEST_F(CoordinatorServiceTest, HeartbeatOfKnownWorkerIsOkAndUnknownIsNotFound) {
  v1::RegisterWorkerResponse response;
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "h:1"), &response).ok());
  const grpc::Status ok = Heartbeat(response.worker_id());
  EXPECT_TRUE(ok.ok()) << ok.error_message();
  const grpc::Status unknown = Heartbeat("actor-424242");
  EXPECT_EQ(unknown.error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_THAT(unknown.error_message(), HasSubstr("actor-424242"));
}

TEST_F(CoordinatorServiceTest, ClusterStatusListsWorkersAndCoordinatorBuild) {
  v1::RegisterWorkerResponse actor;
  v1::RegisterWorkerResponse learner;
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "10.0.0.2:7001"), &actor).ok());
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_LEARNER, "10.0.0.1:7000"), &learner).ok());

  v1::GetClusterStatusResponse status;
  const grpc::Status result = Status(&status);
  ASSERT_TRUE(result.ok()) << result.error_message();
  EXPECT_EQ(status.coordinator_build().version(), DcsVersion());
  ASSERT_EQ(status.coordinator_build().libraries_size(), static_cast<int>(build_.libraries.size()));
  EXPECT_EQ(status.coordinator_build().libraries(0).name(), "grpc");
  EXPECT_EQ(status.coordinator_build().libraries().rbegin()->name(), "sqlite");
  EXPECT_EQ(TimeFromProto(status.coordinator_start_time()), start_time_);

  ASSERT_EQ(status.workers_size(), 2);
  // Learners first.
  EXPECT_EQ(status.workers(0).worker_id(), learner.worker_id());
  EXPECT_EQ(status.workers(0).info().address(), "10.0.0.1:7000");
  EXPECT_EQ(status.workers(0).info().role(), v1::WORKER_ROLE_LEARNER);
  EXPECT_EQ(status.workers(0).state(), v1::WORKER_STATE_ALIVE);
  EXPECT_EQ(status.workers(1).worker_id(), actor.worker_id());
  EXPECT_EQ(status.workers(1).info().address(), "10.0.0.2:7001");
  EXPECT_EQ(status.workers(1).info().hostname(), "node-1");
  EXPECT_EQ(status.workers(1).info().build().version(), "0.1.0+w0rk3r");
  // Registered just now, by the coordinator's clock.
  const absl::Time registered = TimeFromProto(status.workers(1).registered_time());
  EXPECT_LE(registered, absl::Now());
  EXPECT_GT(registered, start_time_);
}

TEST_F(CoordinatorServiceTest, UnregisterRemovesWorkerThenNotFound) {
  v1::RegisterWorkerResponse response;
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "h:1"), &response).ok());
  const grpc::Status first = Unregister(response.worker_id());
  EXPECT_TRUE(first.ok()) << first.error_message();
  EXPECT_TRUE(registry().List(absl::Now()).empty());
  EXPECT_EQ(Unregister(response.worker_id()).error_code(), grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(Heartbeat(response.worker_id()).error_code(), grpc::StatusCode::NOT_FOUND);

  v1::GetClusterStatusResponse status;
  ASSERT_TRUE(Status(&status).ok());
  EXPECT_EQ(status.workers_size(), 0);
}

TEST_F(CoordinatorServiceTest, ServerMetricsCountCallsByMethodAndCode) {
  v1::RegisterWorkerResponse response;
  ASSERT_TRUE(Register(Worker(v1::WORKER_ROLE_ACTOR, "h:1"), &response).ok());
  ASSERT_EQ(Register(Worker(v1::WORKER_ROLE_UNSPECIFIED, "h:1"), &response).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  ASSERT_EQ(Heartbeat("actor-999").error_code(), grpc::StatusCode::NOT_FOUND);

  const std::vector<std::pair<std::string, std::string>> register_labels = {
      {"grpc_service", "dcs.v1.CoordinatorService"},
      {"grpc_method", "RegisterWorker"},
      {"grpc_type", "unary"}};
  auto with_code = [](std::vector<std::pair<std::string, std::string>> labels,
                      const std::string& code) {
    labels.emplace_back("grpc_code", code);
    return labels;
  };
  EXPECT_EQ(CounterValue("grpc_server_started_total", register_labels), 2);
  EXPECT_EQ(CounterValue("grpc_server_handled_total", with_code(register_labels, "OK")), 1);
  EXPECT_EQ(
      CounterValue("grpc_server_handled_total", with_code(register_labels, "INVALID_ARGUMENT")), 1);
  EXPECT_EQ(CounterValue("grpc_server_handled_total",
                         {{"grpc_method", "Heartbeat"}, {"grpc_code", "NOT_FOUND"}}),
            1);
  // Methods not called yet are initialised at zero.
  EXPECT_EQ(CounterValue("grpc_server_handled_total",
                         {{"grpc_method", "UnregisterWorker"}, {"grpc_code", "OK"}}),
            0);
}

TEST_F(CoordinatorServiceTest, MetricsEndpointServesServerMetrics) {
  // As dcs-coordinator wires it: the gRPC server's metrics are scraped from the endpoint.
  absl::StatusOr<std::unique_ptr<MetricsEndpoint>> endpoint =
      MetricsEndpoint::Start("127.0.0.1:0", "coordinator", build_);
  ASSERT_TRUE(endpoint.ok()) << endpoint.status();
  (*endpoint)->AddCollectable(coordinator_->metrics());
  v1::RegisterWorkerResponse response;
  ASSERT_EQ(Register(Worker(v1::WORKER_ROLE_UNSPECIFIED, "h:1"), &response).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);

  const absl::StatusOr<std::string> scraped =
      HttpGet(absl::StrCat("http://127.0.0.1:", (*endpoint)->port(), "/metrics"));
  ASSERT_TRUE(scraped.ok()) << scraped.status();
  EXPECT_THAT(*scraped, ContainsRegex("grpc_server_handled_total\\{[^}]*"
                                     "grpc_code=\"INVALID_ARGUMENT\"[^}]*"
                                     "grpc_method=\"RegisterWorker\"[^}]*\\} 1"));
  EXPECT_THAT(*scraped, HasSubstr("dcs_build_info{"));
}

}  // namespace
}  // namespace dcs::services
