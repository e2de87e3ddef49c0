// Copyright 2026 The DCS Authors.
#include "dcs/proto_json.h"

#include <google/protobuf/struct.pb.h>

#include <limits>
#include <string>

#include "dcs/v1/study.pb.h"
#include "gtest/gtest.h"

namespace dcs {
namespace {

// MessageToJsonString prints a map in its hash order, which a map seeds afresh; a line printed
// twice, or by another process, must read the same.
TEST(ProtoToJsonTest, PrintsAMapsEntriesInKeyOrder) {
  google::protobuf::Struct record;
  std::string expected;
  for (char key = 'a'; key <= 'p'; ++key) {
    (*record.mutable_fields())[std::string(1, key)].set_number_value(key - 'a');
    expected += std::string(expected.empty() ? "" : ",") + '"' + key + "\":" +
                std::to_string(key - 'a');
  }
  EXPECT_EQ(ProtoToJsonLine(record), "{" + expected + "}");
}

// `dcs study ask` prints trial 0 (a zero) and leaves out the value of a trial not complete;
// a complete trial's value may be infinite, which JSON spells as a string.
TEST(ProtoToJsonTest, ALineHoldsEveryFieldButUnsetOptionalOnes) {
  v1::StudyTrialLine line;
  line.set_state("running");
  (*line.mutable_params()->mutable_fields())["shape"].set_string_value("bowl");
  EXPECT_EQ(ProtoToJsonLine(line), R"({"trial":0,"state":"running","params":{"shape":"bowl"}})");
  line.set_value(-std::numeric_limits<double>::infinity());
  EXPECT_EQ(ProtoToJsonLine(line),
            R"({"trial":0,"state":"running","params":{"shape":"bowl"},"value":"-Infinity"})");
}

}  // namespace
}  // namespace dcs
