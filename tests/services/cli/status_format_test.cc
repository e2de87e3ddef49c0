// Copyright 2026 The DCS Authors.
#include "services/cli/status_format.h"

#include <string>
#include <vector>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>

#include "absl/status/status.h"
#include "absl/strings/str_split.h"
#include "absl/time/time.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/time_proto.h"

namespace dcs::services::cli {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

const absl::Time kNow = absl::FromUnixSeconds(1'763'717'400);

v1::Worker MakeWorker(const std::string& id, v1::WorkerRole role, v1::WorkerState state,
                      const std::string& address, absl::Duration silence) {
  v1::Worker worker;
  worker.set_worker_id(id);
  worker.set_state(state);
  worker.mutable_info()->set_role(role);
  worker.mutable_info()->set_address(address);
  worker.mutable_info()->set_hostname("node-" + id);
  worker.mutable_info()->set_pid(1000 + static_cast<int>(id.size()));
  worker.mutable_info()->mutable_build()->set_version("0.1.0+feedbee");
  *worker.mutable_registered_time() = TimeToProto(kNow - absl::Minutes(10));
  *worker.mutable_last_heartbeat_time() = TimeToProto(kNow - silence);
  return worker;
}

v1::GetClusterStatusResponse SampleStatus() {
  v1::GetClusterStatusResponse status;
  status.mutable_coordinator_build()->set_version("0.1.0+c00rd1n");
  auto* library = status.mutable_coordinator_build()->add_libraries();
  library->set_name("sqlite");
  library->set_version("3.40.1");
  *status.mutable_coordinator_start_time() = TimeToProto(kNow - absl::Seconds(125));
  *status.add_workers() = MakeWorker("learner-1", v1::WORKER_ROLE_LEARNER, v1::WORKER_STATE_LOST,
                                     "10.0.0.5:50052", absl::Seconds(12));
  *status.add_workers() = MakeWorker("actor-2", v1::WORKER_ROLE_ACTOR, v1::WORKER_STATE_ALIVE,
                                     "10.0.0.6:50053", absl::Milliseconds(400));
  return status;
}

// The lines of `text`, without the empty string after the final newline.
std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines = absl::StrSplit(text, '\n');
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

// The line of `lines` that contains `needle`, or "" if none does.
std::string LineWith(const std::vector<std::string>& lines, const std::string& needle) {
  for (const std::string& line : lines) {
    if (line.find(needle) != std::string::npos) return line;
  }
  return "";
}

TEST(FormatClusterStatusTest, TableListsEveryWorker) {
  const std::string text =
      FormatClusterStatus(SampleStatus(), "127.0.0.1:50051", kNow, OutputFormat::kTable);
  const std::vector<std::string> lines = Lines(text);

  const std::string learner = LineWith(lines, "learner-1");
  ASSERT_FALSE(learner.empty()) << text;
  std::vector<std::string> cells = absl::StrSplit(learner, ' ', absl::SkipEmpty());
  ASSERT_GE(cells.size(), 8u) << learner;
  EXPECT_EQ(cells[0], "learner");
  EXPECT_EQ(cells[1], "learner-1");
  EXPECT_EQ(cells[2], "10.0.0.5:50052");
  EXPECT_EQ(cells[3], "lost");
  EXPECT_EQ(cells[4], "12.0s");
  EXPECT_EQ(cells[5], "ago");
  EXPECT_EQ(cells[6], "node-learner-1");
  EXPECT_EQ(cells[7], "1009");

  const std::string actor = LineWith(lines, "actor-2");
  ASSERT_FALSE(actor.empty()) << text;
  cells = absl::StrSplit(actor, ' ', absl::SkipEmpty());
  ASSERT_GE(cells.size(), 5u) << actor;
  EXPECT_EQ(cells[0], "actor");
  EXPECT_EQ(cells[2], "10.0.0.6:50053");
  EXPECT_EQ(cells[3], "alive");
  EXPECT_EQ(cells[4], "0.4s");
}

TEST(FormatClusterStatusTest, TableHeaderNamesCoordinatorAndAlignsColumns) {
  const std::string text =
      FormatClusterStatus(SampleStatus(), "127.0.0.1:50051", kNow, OutputFormat::kTable);
  const std::vector<std::string> lines = Lines(text);
  ASSERT_GE(lines.size(), 5u) << text;
  EXPECT_THAT(lines[0], HasSubstr("127.0.0.1:50051"));
  EXPECT_THAT(lines[0], HasSubstr("0.1.0+c00rd1n"));
  EXPECT_THAT(lines[0], HasSubstr("up 2m5s"));
  const std::string header = LineWith(lines, "ADDRESS");
  ASSERT_FALSE(header.empty()) << text;
  // Every column starts at the same offset on every row.
  const size_t address_column = header.find("ADDRESS");
  const size_t state_column = header.find("STATE");
  EXPECT_EQ(LineWith(lines, "learner-1").find("10.0.0.5:50052"), address_column);
  EXPECT_EQ(LineWith(lines, "actor-2").find("10.0.0.6:50053"), address_column);
  EXPECT_EQ(LineWith(lines, "learner-1").find("lost"), state_column);
  EXPECT_EQ(LineWith(lines, "actor-2").find("alive"), state_column);
}

TEST(FormatClusterStatusTest, TableSaysNoWorkersWhenEmpty) {
  v1::GetClusterStatusResponse status = SampleStatus();
  status.clear_workers();
  const std::string text =
      FormatClusterStatus(status, "127.0.0.1:50051", kNow, OutputFormat::kTable);
  EXPECT_THAT(text, HasSubstr("no workers"));
  EXPECT_THAT(text, Not(HasSubstr("ADDRESS")));
  EXPECT_THAT(text, HasSubstr("0.1.0+c00rd1n"));
}

TEST(FormatClusterStatusTest, FutureHeartbeatShowsAsZeroAge) {
  v1::GetClusterStatusResponse status;
  *status.add_workers() = MakeWorker("actor-1", v1::WORKER_ROLE_ACTOR, v1::WORKER_STATE_ALIVE,
                                     "h:1", -absl::Seconds(3));
  const std::string text = FormatClusterStatus(status, "h:0", kNow, OutputFormat::kTable);
  EXPECT_THAT(LineWith(Lines(text), "actor-1"), HasSubstr(" 0.0s ago"));
}

// As every command's -o json (command_output.h): proto field names, numbers, words for states.
TEST(FormatClusterStatusTest, JsonIsTheCommandsJson) {
  const v1::GetClusterStatusResponse status = SampleStatus();
  const std::string json =
      FormatClusterStatus(status, "127.0.0.1:50051", kNow, OutputFormat::kJson);
  EXPECT_THAT(json, HasSubstr("\"worker_id\""));
  EXPECT_THAT(json, HasSubstr("\"coordinator_build\""));
  EXPECT_THAT(json, HasSubstr("\"state\":\"lost\""));
  EXPECT_THAT(json, HasSubstr("\"role\":\"learner\""));
  EXPECT_THAT(json, ::testing::ContainsRegex("\"pid\":[0-9]+,"));
  EXPECT_EQ(json.find('\n'), json.size() - 1) << "one line";

  google::protobuf::Value parsed;
  const auto result = google::protobuf::util::JsonStringToMessage(json, &parsed);
  ASSERT_TRUE(result.ok()) << result.ToString();
  EXPECT_EQ(parsed.struct_value().fields().at("workers").list_value().values_size(),
            status.workers_size());
}

}  // namespace
}  // namespace dcs::services::cli
