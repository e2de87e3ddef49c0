// Copyright 2026 The DCS Authors.
#include "services/cli/cli_command.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services::cli {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Pair;

TEST(CliCommandTest, NumberListsAreFiniteNumbers) {
  EXPECT_THAT(*ParseNumberList("0.35,0.75", "--range"), ElementsAre(0.35, 0.75));
  EXPECT_THAT(*ParseNumberList("-1e-3", "--init"), ElementsAre(-1e-3));
  for (const char* bad : {"0.35,", "a,1", "nan", "1,inf"}) {
    const absl::Status status = ParseNumberList(bad, "--range").status();
    EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument) << bad;
    EXPECT_THAT(status.message(), HasSubstr("--range: '")) << bad;
  }
}

TEST(CliCommandTest, AssignmentsAreNamesWithFiniteValuesGivenOnce) {
  EXPECT_THAT(*ParseAssignments({"length=1.3", "gravity=9"}, "--set"),
              ElementsAre(Pair("gravity", 9.0), Pair("length", 1.3)));
  EXPECT_THAT(ParseAssignments({"length"}, "--set").status().message(),
              HasSubstr("--set: expected name=value with a finite number, got 'length'"));
  EXPECT_THAT(ParseAssignments({"length=nan"}, "--set").status().message(),
              HasSubstr("got 'length=nan'"));
  EXPECT_THAT(ParseAssignments({"length=1", "length=2"}, "--set").status().message(),
              HasSubstr("--set: 'length' is given twice"));
}

}  // namespace
}  // namespace dcs::services::cli
