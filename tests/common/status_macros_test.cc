// Copyright 2026 The DCS Authors.
#include "common/status_macros.h"

#include <memory>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "gtest/gtest.h"

namespace dcs::common {
namespace {

// Counts how many times it is called, so a test can tell whether an early return happened.
struct Calls {
  int count = 0;
  absl::Status Step(absl::Status result) {
    ++count;
    return result;
  }
};

absl::Status TwoSteps(Calls& calls, absl::Status first, absl::Status second) {
  DCS_RETURN_IF_ERROR(calls.Step(first));
  DCS_RETURN_IF_ERROR(calls.Step(second));
  return absl::OkStatus();
}

TEST(ReturnIfErrorTest, OkStatusesFallThrough) {
  Calls calls;
  EXPECT_TRUE(TwoSteps(calls, absl::OkStatus(), absl::OkStatus()).ok());
  EXPECT_EQ(calls.count, 2);
}

TEST(ReturnIfErrorTest, FirstErrorIsReturnedAndStopsTheFunction) {
  Calls calls;
  const absl::Status status =
      TwoSteps(calls, absl::NotFoundError("no such run"), absl::InternalError("never reached"));
  EXPECT_EQ(status, absl::NotFoundError("no such run"));
  EXPECT_EQ(calls.count, 1);
}

TEST(ReturnIfErrorTest, SecondErrorIsReturned) {
  Calls calls;
  const absl::Status status =
      TwoSteps(calls, absl::OkStatus(), absl::DataLossError("torn checkpoint"));
  EXPECT_EQ(status, absl::DataLossError("torn checkpoint"));
  EXPECT_EQ(calls.count, 2);
}

// Nested uses: each macro's argument is a lambda that uses the macros again. This file is
// built with -Wshadow -Werror, so the test is first that it compiles: hidden variables of
// nested uses would otherwise shadow each other.
absl::Status Nested(Calls& calls, absl::Status inner) {
  DCS_RETURN_IF_ERROR([&]() -> absl::Status {
    DCS_RETURN_IF_ERROR([&]() -> absl::Status {
      DCS_RETURN_IF_ERROR(calls.Step(inner));
      return calls.Step(absl::OkStatus());
    }());
    return absl::OkStatus();
  }());
  return calls.Step(absl::OkStatus());
}

TEST(ReturnIfErrorTest, NestedUsesReturnTheInnermostError) {
  Calls calls;
  EXPECT_TRUE(Nested(calls, absl::OkStatus()).ok());
  EXPECT_EQ(calls.count, 3);
  calls.count = 0;
  EXPECT_EQ(Nested(calls, absl::AbortedError("lease moved")), absl::AbortedError("lease moved"));
  EXPECT_EQ(calls.count, 1);
}

absl::StatusOr<int> Half(int value) {
  if (value % 2 != 0) return absl::InvalidArgumentError(absl::StrCat(value, " is odd"));
  return value / 2;
}

// Uses the macro twice in one function (two hidden variables must not collide), once
// declaring a new variable and once assigning to an existing one.
absl::StatusOr<int> Quarter(int value, std::string* trace) {
  DCS_ASSIGN_OR_RETURN(const int half, Half(value));
  trace->append("half ");
  int quarter = -1;
  DCS_ASSIGN_OR_RETURN(quarter, Half(half));
  trace->append("quarter");
  return quarter;
}

TEST(AssignOrReturnTest, AssignsValuesWhenUsedTwice) {
  std::string trace;
  const absl::StatusOr<int> result = Quarter(12, &trace);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_EQ(*result, 3);
  EXPECT_EQ(trace, "half quarter");
}

TEST(AssignOrReturnTest, FirstErrorPropagates) {
  std::string trace;
  const absl::StatusOr<int> result = Quarter(7, &trace);
  EXPECT_EQ(result.status(), absl::InvalidArgumentError("7 is odd"));
  EXPECT_EQ(trace, "");
}

TEST(AssignOrReturnTest, SecondErrorPropagates) {
  std::string trace;
  const absl::StatusOr<int> result = Quarter(6, &trace);
  EXPECT_EQ(result.status(), absl::InvalidArgumentError("3 is odd"));
  EXPECT_EQ(trace, "half ");
}

// DCS_ASSIGN_OR_RETURN inside a lambda given to DCS_ASSIGN_OR_RETURN.
absl::StatusOr<int> NestedQuarter(int value) {
  DCS_ASSIGN_OR_RETURN(const int quarter, [&]() -> absl::StatusOr<int> {
    DCS_ASSIGN_OR_RETURN(const int half, Half(value));
    return Half(half);
  }());
  return quarter;
}

TEST(AssignOrReturnTest, Nests) {
  EXPECT_EQ(NestedQuarter(12).value_or(-1), 3);
  EXPECT_EQ(NestedQuarter(6).status(), absl::InvalidArgumentError("3 is odd"));
}

absl::StatusOr<std::unique_ptr<std::string>> MakeName(bool ok) {
  if (!ok) return absl::UnavailableError("down");
  return std::make_unique<std::string>("learner-1");
}

absl::Status MoveOnly(bool ok, std::string* out) {
  DCS_ASSIGN_OR_RETURN(std::unique_ptr<std::string> name, MakeName(ok));
  *out = *name;
  return absl::OkStatus();
}

TEST(AssignOrReturnTest, WorksWithMoveOnlyValuesInStatusFunction) {
  std::string out;
  EXPECT_TRUE(MoveOnly(true, &out).ok());
  EXPECT_EQ(out, "learner-1");
  out.clear();
  EXPECT_EQ(MoveOnly(false, &out), absl::UnavailableError("down"));
  EXPECT_EQ(out, "");
}

}  // namespace
}  // namespace dcs::common
