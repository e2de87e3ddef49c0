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

}  // namespace
}  // namespace dcs::common
