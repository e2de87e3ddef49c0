// Copyright 2026 The DCS Authors.
//
// CoordinatorService's removals and study list, served in this process: DeleteRuns and
// DeleteSweeps answer what they removed and take the runs' directories with them, refuse what
// still runs (FAILED_PRECONDITION saying how to stop it) and unknown ids (NOT_FOUND); a watch of
// what was removed ends NOT_FOUND; ListStudies lists every study, a study sweep's with its sweep.

#include <grpcpp/grpcpp.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/channel.h"
#include "services/coordinator/study_proto.h"
#include "services/log.h"
#include "tests/testing/in_process_coordinator.h"
#include "tests/testing/temp_dir.h"

namespace dcs::services {
namespace {

using dcs::testing::InProcessCoordinator;
using ::testing::HasSubstr;

constexpr absl::Duration kRpcTimeout = absl::Seconds(20);

constexpr char kConfig[] =
    "env: cartpole\ntotal_timesteps: 2048\nevaluation: {contexts: {id: [0.5]}}\n";

// Two trials of one seed.
constexpr char kSpec[] = R"(name: small
seeds: 1
env: cartpole
total_timesteps: 2048
evaluation: {contexts: {id: [0.5]}}
conditions:
  - name: static
  - schedule: {family: sinusoidal, period: 40}
)";

// A search of two trials: a study sweep.
constexpr char kSearchSpec[] = R"(name: search
seeds: 1
env: cartpole
total_timesteps: 2048
evaluation: {contexts: {id: [0.5]}}
conditions:
  - name: base
    schedule: {family: sinusoidal, period: 40}
study:
  trials: 2
  parallel: 1
  sampler: random
  space:
    parameters:
      - {name: "schedule.period", type: int, low: 20, high: 80}
)";

class CoordinatorRemovalTest : public dcs::testing::TempDirTest {
 protected:
  void SetUp() override {
    dcs::testing::TempDirTest::SetUp();
    ConfigureLogging({.component = "test", .min_level = LogLevel::kError});
    std::filesystem::create_directories(Path("data"));
    absl::StatusOr<std::unique_ptr<InProcessCoordinator>> coordinator =
        InProcessCoordinator::Start({.serving = true, .data_dir = Path("data")});
    ASSERT_TRUE(coordinator.ok()) << coordinator.status();
    coordinator_ = *std::move(coordinator);
    stub_ = v1::CoordinatorService::NewStub(OpenChannel(coordinator_->address()));
  }

  void TearDown() override {
    stub_.reset();
    coordinator_.reset();
    dcs::testing::TempDirTest::TearDown();
  }

  // `method(request)` with a deadline; the response in `response`.
  template <typename Request, typename Response>
  grpc::Status Call(grpc::Status (v1::CoordinatorService::Stub::*method)(grpc::ClientContext*,
                                                                         const Request&,
                                                                         Response*),
                    const Request& request, Response& response) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    return ((*stub_).*method)(&context, request, &response);
  }

  std::string SubmitRun(const std::string& request_id) {
    v1::SubmitRunRequest request;
    request.set_request_id(request_id);
    request.set_config(kConfig);
    v1::SubmitRunResponse response;
    const grpc::Status status = Call(&v1::CoordinatorService::Stub::SubmitRun, request, response);
    EXPECT_TRUE(status.ok()) << status.error_message();
    return response.run().run_id();
  }

  grpc::Status DeleteRuns(const std::vector<std::string>& run_ids,
                          v1::DeleteRunsResponse& removed) {
    v1::DeleteRunsRequest request;
    for (const std::string& run_id : run_ids) request.add_run_ids(run_id);
    return Call(&v1::CoordinatorService::Stub::DeleteRuns, request, removed);
  }

  grpc::Status DeleteSweep(const std::string& sweep_id, v1::DeleteSweepsResponse& removed) {
    v1::DeleteSweepsRequest request;
    request.add_sweep_ids(sweep_id);
    return Call(&v1::CoordinatorService::Stub::DeleteSweeps, request, removed);
  }

  bool HasDirectory(const std::string& run_id) {
    return std::filesystem::exists(Path("data/runs/" + run_id));
  }

  // The status a watch of `id` ends with, having sent nothing.
  template <typename Request, typename Update>
  grpc::Status WatchEnd(
      std::unique_ptr<grpc::ClientReader<Update>> (v1::CoordinatorService::Stub::*watch)(
          grpc::ClientContext*, const Request&),
      const Request& request) {
    grpc::ClientContext context;
    SetTimeout(context, kRpcTimeout);
    std::unique_ptr<grpc::ClientReader<Update>> reader = ((*stub_).*watch)(&context, request);
    Update update;
    EXPECT_FALSE(reader->Read(&update));
    return reader->Finish();
  }

  std::unique_ptr<InProcessCoordinator> coordinator_;
  std::unique_ptr<v1::CoordinatorService::Stub> stub_;
};

TEST_F(CoordinatorRemovalTest, AnEndedRunIsRemovedWithItsDirectoryAndItsWatchEndsNotFound) {
  const std::string run_id = SubmitRun("a");
  const std::string other = SubmitRun("b");
  ASSERT_TRUE(HasDirectory(run_id));
  v1::DeleteRunsResponse removed;
  const grpc::Status queued = DeleteRuns({run_id}, removed);
  EXPECT_EQ(queued.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_EQ(queued.error_message(), "run-1 is queued: stop it first with `dcs runs cancel run-1`");
  EXPECT_TRUE(HasDirectory(run_id));

  v1::CancelRunRequest cancel;
  cancel.set_run_id(run_id);
  v1::CancelRunResponse cancelled;
  ASSERT_TRUE(Call(&v1::CoordinatorService::Stub::CancelRun, cancel, cancelled).ok());
  const grpc::Status status = DeleteRuns({run_id}, removed);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(removed.runs_size(), 1);
  EXPECT_EQ(removed.runs(0).run_id(), run_id);
  EXPECT_EQ(removed.runs(0).state(), v1::RUN_STATE_CANCELLED);
  EXPECT_FALSE(HasDirectory(run_id));
  EXPECT_TRUE(HasDirectory(other));

  v1::GetRunRequest get;
  get.set_run_id(run_id);
  v1::GetRunResponse got;
  EXPECT_EQ(Call(&v1::CoordinatorService::Stub::GetRun, get, got).error_code(),
            grpc::StatusCode::NOT_FOUND);
  v1::WatchRunRequest watch;
  watch.set_run_id(run_id);
  EXPECT_EQ(WatchEnd(&v1::CoordinatorService::Stub::WatchRun, watch).error_code(),
            grpc::StatusCode::NOT_FOUND);
  EXPECT_EQ(DeleteRuns({run_id}, removed).error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(CoordinatorRemovalTest, AnEndedSweepIsRemovedWithItsRunsAndItsWatchEndsNotFound) {
  v1::SubmitSweepRequest submit;
  submit.set_request_id("s");
  submit.set_spec(kSpec);
  v1::SubmitSweepResponse submitted;
  const grpc::Status status = Call(&v1::CoordinatorService::Stub::SubmitSweep, submit, submitted);
  ASSERT_TRUE(status.ok()) << status.error_message();
  const std::string sweep_id = submitted.sweep().sweep_id();
  v1::DeleteSweepsResponse removed;
  const grpc::Status queued = DeleteSweep(sweep_id, removed);
  EXPECT_EQ(queued.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
  EXPECT_THAT(queued.error_message(), HasSubstr("`dcs sweeps cancel sweep-1`"));

  v1::CancelSweepRequest cancel;
  cancel.set_sweep_id(sweep_id);
  v1::CancelSweepResponse cancelled;
  ASSERT_TRUE(Call(&v1::CoordinatorService::Stub::CancelSweep, cancel, cancelled).ok());
  ASSERT_TRUE(DeleteSweep(sweep_id, removed).ok());
  ASSERT_EQ(removed.sweeps_size(), 1);
  EXPECT_EQ(removed.sweeps(0).sweep_id(), sweep_id);
  EXPECT_EQ(removed.sweeps(0).state(), v1::SWEEP_STATE_CANCELLED);
  ASSERT_EQ(removed.runs_size(), 2);
  EXPECT_EQ(removed.runs(1).run_id(), "run-2");
  EXPECT_FALSE(HasDirectory("run-1"));
  EXPECT_FALSE(HasDirectory("run-2"));

  v1::WatchSweepRequest watch;
  watch.set_sweep_id(sweep_id);
  EXPECT_EQ(WatchEnd(&v1::CoordinatorService::Stub::WatchSweep, watch).error_code(),
            grpc::StatusCode::NOT_FOUND);
  v1::ListSweepsResponse sweeps;
  ASSERT_TRUE(
      Call(&v1::CoordinatorService::Stub::ListSweeps, v1::ListSweepsRequest(), sweeps).ok());
  EXPECT_EQ(sweeps.sweeps_size(), 0);
  EXPECT_EQ(DeleteSweep(sweep_id, removed).error_code(), grpc::StatusCode::NOT_FOUND);
}

TEST_F(CoordinatorRemovalTest, ListStudiesListsEveryStudyOldestFirstWithItsSweep) {
  v1::SubmitSweepRequest submit;
  submit.set_request_id("search");
  submit.set_spec(kSearchSpec);
  v1::SubmitSweepResponse submitted;
  const grpc::Status search = Call(&v1::CoordinatorService::Stub::SubmitSweep, submit, submitted);
  ASSERT_TRUE(search.ok()) << search.error_message();
  for (const char* name : {"first", "second"}) {
    v1::CreateStudyRequest create;
    create.set_request_id(name);
    *create.mutable_study() = StudyToProto(
        {.submission = {.name = name,
                        .space = "parameters:\n  - {name: x, type: float, low: 0, high: 1}\n",
                        .direction = coordinator::Direction::kMaximize}});
    v1::CreateStudyResponse created;
    const grpc::Status status = Call(&v1::CoordinatorService::Stub::CreateStudy, create, created);
    ASSERT_TRUE(status.ok()) << status.error_message();
  }
  v1::ListStudiesResponse listed;
  ASSERT_TRUE(
      Call(&v1::CoordinatorService::Stub::ListStudies, v1::ListStudiesRequest(), listed).ok());
  ASSERT_EQ(listed.studies_size(), 3);
  EXPECT_EQ(listed.studies(0).study_id(), "study-1");
  EXPECT_EQ(listed.studies(0).name(), "search");
  EXPECT_EQ(listed.studies(0).sweep_id(), "sweep-1");
  EXPECT_EQ(listed.studies(1).name(), "first");
  EXPECT_EQ(listed.studies(2).name(), "second");
  EXPECT_EQ(listed.studies(2).direction(), "maximize");
  EXPECT_EQ(listed.studies(2).sweep_id(), "");
}

}  // namespace
}  // namespace dcs::services
