// Copyright 2026 The DCS Authors.
//
// CoordinatorService's watches (services/coordinator/coordinator_watch.cc), served in this
// process: a WatchRun stream sends the run at once, then the run after each change a learner
// makes (its lease, its progress, its end), and ends OK with the ended run; an unknown run is
// NOT_FOUND; a watcher that goes is no longer counted in dcs_watchers.

#include <grpcpp/grpcpp.h>
#include <prometheus/metric_family.h>

#include <memory>
#include <string>

#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "gtest/gtest.h"
#include "services/channel.h"
#include "services/log.h"
#include "tests/testing/eventually.h"
#include "tests/testing/in_process_coordinator.h"

namespace dcs::services {
namespace {

using dcs::testing::Eventually;
using dcs::testing::InProcessCoordinator;

// Far above what any call takes here: a watch that misses a change waits for it this long.
constexpr absl::Duration kRpcTimeout = absl::Seconds(20);

class CoordinatorWatchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ConfigureLogging({.component = "test", .min_level = LogLevel::kError});
    absl::StatusOr<std::unique_ptr<InProcessCoordinator>> coordinator =
        InProcessCoordinator::Start({.serving = true});
    ASSERT_TRUE(coordinator.ok()) << coordinator.status();
    coordinator_ = *std::move(coordinator);
    stub_ = v1::CoordinatorService::NewStub(OpenChannel(coordinator_->address()));
  }

  // The run submitted, queued.
  std::string SubmitRun() {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    v1::SubmitRunRequest request;
    request.set_request_id("watched");
    request.set_config(
        "env: cartpole\ntotal_timesteps: 2048\nevaluation: {contexts: {id: [0.5]}}\n");
    v1::SubmitRunResponse response;
    const grpc::Status status = stub_->SubmitRun(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.run().run_id();
  }

  v1::Lease AcquireRun() {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    v1::AcquireRunRequest request;
    request.set_holder("learner-1");
    request.set_address("127.0.0.1:1");
    request.set_numerics("kernels");
    v1::AcquireRunResponse response;
    const grpc::Status status = stub_->AcquireRun(&context, request, &response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.lease();
  }

  std::unique_ptr<grpc::ClientReader<v1::GetRunResponse>> Watch(grpc::ClientContext& context,
                                                                 const std::string& run_id) {
    v1::WatchRunRequest request;
    request.set_run_id(run_id);
    return stub_->WatchRun(&context, request);
  }

  double RunWatchers() {
    for (const prometheus::MetricFamily& family : coordinator_->metrics()->Collect()) {
      if (family.name != "dcs_watchers") continue;
      for (const prometheus::ClientMetric& metric : family.metric) {
        if (metric.label.size() == 1 && metric.label[0].value == "run") {
          return metric.gauge.value;
        }
      }
    }
    return -1;
  }

  std::unique_ptr<InProcessCoordinator> coordinator_;
  std::unique_ptr<v1::CoordinatorService::Stub> stub_;
};

TEST_F(CoordinatorWatchTest, AWatchSendsTheRunThenEachChangeOfItsLearnerAndEndsWithIt) {
  const std::string run_id = SubmitRun();
  grpc::ClientContext context;
  SetTimeout(context, kRpcTimeout);
  std::unique_ptr<grpc::ClientReader<v1::GetRunResponse>> watch = Watch(context, run_id);
  v1::GetRunResponse update;
  ASSERT_TRUE(watch->Read(&update));
  EXPECT_EQ(update.run().run_id(), run_id);
  EXPECT_EQ(update.run().state(), v1::RUN_STATE_QUEUED);
  EXPECT_EQ(RunWatchers(), 1);

  const v1::Lease lease = AcquireRun();
  ASSERT_TRUE(watch->Read(&update));
  EXPECT_EQ(update.run().state(), v1::RUN_STATE_RUNNING);

  {
    grpc::ClientContext report;
    SetTimeout(report, kRpcTimeout);
    v1::ReportProgressRequest progress;
    *progress.mutable_lease() = lease;
    progress.mutable_progress()->set_timesteps(512);
    progress.mutable_progress()->set_total_timesteps(2048);
    v1::ReportProgressResponse reported;
    ASSERT_TRUE(stub_->ReportProgress(&report, progress, &reported).ok());
  }
  ASSERT_TRUE(watch->Read(&update));
  EXPECT_EQ(update.run().progress().timesteps(), 512);

  {
    grpc::ClientContext finish;
    SetTimeout(finish, kRpcTimeout);
    v1::FinishRunRequest finished;
    *finished.mutable_lease() = lease;
    finished.set_state(v1::RUN_STATE_COMPLETED);
    v1::FinishRunResponse response;
    ASSERT_TRUE(stub_->FinishRun(&finish, finished, &response).ok());
  }
  ASSERT_TRUE(watch->Read(&update));
  EXPECT_EQ(update.run().state(), v1::RUN_STATE_COMPLETED);
  EXPECT_FALSE(watch->Read(&update));
  const grpc::Status status = watch->Finish();
  EXPECT_TRUE(status.ok()) << status.error_message();
  EXPECT_TRUE(Eventually([&] { return RunWatchers() == 0; }));
}

TEST_F(CoordinatorWatchTest, AWatchOfAnUnknownRunIsNotFound) {
  grpc::ClientContext context;
  SetTimeout(context, kRpcTimeout);
  std::unique_ptr<grpc::ClientReader<v1::GetRunResponse>> watch = Watch(context, "run-404");
  v1::GetRunResponse update;
  EXPECT_FALSE(watch->Read(&update));
  EXPECT_EQ(watch->Finish().error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(CoordinatorWatchTest, AWatcherThatCancelsIsReleased) {
  const std::string run_id = SubmitRun();
  grpc::ClientContext context;
  std::unique_ptr<grpc::ClientReader<v1::GetRunResponse>> watch = Watch(context, run_id);
  v1::GetRunResponse update;
  ASSERT_TRUE(watch->Read(&update));
  EXPECT_EQ(RunWatchers(), 1);
  context.TryCancel();
  EXPECT_FALSE(watch->Read(&update));
  EXPECT_EQ(watch->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_TRUE(Eventually([&] { return RunWatchers() == 0; }));
}

}  // namespace
}  // namespace dcs::services
