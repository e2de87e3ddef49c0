// Copyright 2026 The DCS Authors.
#include "common/status_util.h"

#include "absl/status/status.h"
#include "gtest/gtest.h"

namespace dcs::common {
namespace {

TEST(AnnotateTest, PrefixesMessageAndKeepsCode) {
  const absl::Status annotated =
      Annotate(absl::NotFoundError("no such file"), "reading config.yaml");
  EXPECT_EQ(annotated.code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(annotated.message(), "reading config.yaml: no such file");
}

TEST(AnnotateTest, NestsOutermostContextFirst) {
  const absl::Status annotated =
      Annotate(Annotate(absl::UnavailableError("connection refused"), "heartbeat"), "agent");
  EXPECT_EQ(annotated.code(), absl::StatusCode::kUnavailable);
  EXPECT_EQ(annotated.message(), "agent: heartbeat: connection refused");
}

TEST(AnnotateTest, KeepsEveryCode) {
  for (int code = 1; code <= 16; ++code) {
    const absl::Status status(static_cast<absl::StatusCode>(code), "reason");
    EXPECT_EQ(Annotate(status, "context").code(), status.code()) << status;
  }
}

TEST(AnnotateTest, OkStaysOk) {
  const absl::Status annotated = Annotate(absl::OkStatus(), "context");
  EXPECT_TRUE(annotated.ok());
  EXPECT_EQ(annotated.message(), "");
}

TEST(ErrorFieldTest, NestedCallersAddTheirPartInFront) {
  const absl::Status status = ErrorInField(
      ErrorInField(absl::InvalidArgumentError("period must be at least 1, got 0"), "period"),
      "parts[1]");
  EXPECT_EQ(ErrorField(status), "parts[1].period");
  EXPECT_EQ(status.message(), "period must be at least 1, got 0");
  EXPECT_EQ(status.code(), absl::StatusCode::kInvalidArgument);
}

TEST(ErrorFieldTest, AbsentUnlessRecordedAndKeptByAnnotate) {
  EXPECT_EQ(ErrorField(absl::InvalidArgumentError("no field")), std::nullopt);
  EXPECT_TRUE(ErrorInField(absl::OkStatus(), "period").ok());
  const absl::Status annotated =
      Annotate(ErrorInField(absl::InvalidArgumentError("bad"), "period"), "stage 2");
  EXPECT_EQ(annotated.message(), "stage 2: bad");
  EXPECT_EQ(ErrorField(annotated), "period");
}

}  // namespace
}  // namespace dcs::common
