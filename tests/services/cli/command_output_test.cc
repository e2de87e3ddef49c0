// Copyright 2026 The DCS Authors.
#include "services/cli/command_output.h"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dcs/v1/run.pb.h"
#include "dcs/v1/study.pb.h"
#include "dcs/v1/sweep.pb.h"
#include "dcs/v1/trajectory.pb.h"
#include "gtest/gtest.h"

namespace dcs::services::cli {
namespace {

TEST(EnumWordTest, DropsTheEnumsPrefixInLowerCase) {
  EXPECT_EQ(EnumWordOf(v1::SWEEP_STATE_COMPLETED), "completed");
  EXPECT_EQ(EnumWordOf(v1::RUN_STATE_QUEUED), "queued");
  EXPECT_EQ(EnumWordOf(v1::D_TYPE_FLOAT32), "float32");
  EXPECT_EQ(EnumWordOf(static_cast<v1::RunState>(42)), "42");
}

// Nested messages, 64-bit integers (the largest too, exactly) and an enum; a string of digits
// stays a string, and a timestamp prints as protobuf prints it.
TEST(CommandJsonTest, PrintsIntegersAsNumbersAndEnumsAsWords) {
  v1::Run run;
  run.set_run_id("12");
  run.set_seed(std::numeric_limits<uint64_t>::max());
  run.set_state(v1::RUN_STATE_COMPLETED);
  run.mutable_progress()->set_timesteps(-3);
  run.mutable_create_time()->set_seconds(1);
  const std::string json = CommandJson(run);
  EXPECT_NE(json.find(R"("run_id":"12")"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("seed":18446744073709551615,)"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("state":"completed")"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("progress":{"timesteps":-3,"total_timesteps":0,)"), std::string::npos)
      << json;
  EXPECT_NE(json.find(R"("create_time":"1970-01-01T00:00:01Z")"), std::string::npos) << json;
}

TEST(CommandJsonTest, RewritesRepeatedFieldsAndMapValuesButNotMapKeys) {
  v1::Tensor tensor;
  tensor.set_dtype(v1::D_TYPE_UINT8);
  tensor.add_shape(2);
  tensor.add_shape(3);
  EXPECT_EQ(CommandJson(tensor), R"({"dtype":"uint8","shape":[2,3],"data":""})");
  v1::Study study;
  (*study.mutable_trials_by_state())["complete"] = 4;
  (*study.mutable_best()->mutable_reported())[100] = 0.5;
  const std::string json = CommandJson(study);
  EXPECT_NE(json.find(R"("trials_by_state":{"complete":4})"), std::string::npos) << json;
  EXPECT_NE(json.find(R"("reported":{"100":0.5})"), std::string::npos) << json;
}

TEST(FormatRowsTest, CsvAndJsonLinesNameColumnsAfterTheHeader) {
  const std::vector<std::vector<std::string>> rows = {
      {"RUN", "STEPS/S", "LAST HEARTBEAT"}, {"run-1", "12.5", "a, b"}, {"run-2", "-", "1e400"}};
  EXPECT_EQ(FormatRows(rows, OutputFormat::kCsv),
            "run,steps_s,last_heartbeat\nrun-1,12.5,\"a, b\"\nrun-2,-,1e400\n");
  EXPECT_EQ(FormatRows(rows, OutputFormat::kJson),
            R"({"last_heartbeat":"a, b","run":"run-1","steps_s":12.5})"
            "\n"
            R"({"last_heartbeat":"1e400","run":"run-2","steps_s":"-"})"
            "\n");
  EXPECT_EQ(FormatRows(rows, OutputFormat::kTable),
            "RUN    STEPS/S  LAST HEARTBEAT\nrun-1  12.5     a, b\nrun-2  -        1e400\n");
}

}  // namespace
}  // namespace dcs::services::cli
