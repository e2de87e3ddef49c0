// Copyright 2026 The DCS Authors.
#include "services/exit_codes.h"

#include <sysexits.h>

#include <set>

#include "absl/status/status.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

TEST(ExitCodeForTest, MapsCodesToSysexitsValues) {
  EXPECT_EQ(ExitCodeFor(absl::InvalidArgumentError("x")), kExitDataError);
  EXPECT_EQ(ExitCodeFor(absl::NotFoundError("x")), kExitNoInput);
  EXPECT_EQ(ExitCodeFor(absl::UnavailableError("x")), kExitUnavailable);
  EXPECT_EQ(ExitCodeFor(absl::DeadlineExceededError("x")), kExitUnavailable);
  EXPECT_EQ(ExitCodeFor(absl::UnauthenticatedError("x")), kExitNoPermission);
  EXPECT_EQ(ExitCodeFor(absl::PermissionDeniedError("x")), kExitNoPermission);
}

TEST(ExitCodeForTest, EverythingElseIsGenericFailure) {
  for (const absl::Status& status :
       {absl::InternalError("x"), absl::UnknownError("x"),
        absl::FailedPreconditionError("x"), absl::ResourceExhaustedError("x"),
        absl::CancelledError("x"), absl::DataLossError("x"), absl::AlreadyExistsError("x")}) {
    EXPECT_EQ(ExitCodeFor(status), kExitFailure) << status;
  }
}

// The command line, not the data it names: usage, and printed without its mark.
TEST(ExitCodeForTest, AUsageErrorIsUsage) {
  const absl::Status usage = UsageError("--config is required");
  EXPECT_EQ(usage.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(ExitCodeFor(usage), kExitUsage);
  EXPECT_EQ(usage.ToString(absl::StatusToStringMode::kWithNoExtraData),
            "INVALID_ARGUMENT: --config is required");
}

TEST(ExitCodesTest, FollowSysexitsWhereOneFits) {
  EXPECT_EQ(kExitOk, EX_OK);
  EXPECT_EQ(kExitDataError, EX_DATAERR);
  EXPECT_EQ(kExitNoInput, EX_NOINPUT);
  EXPECT_EQ(kExitUnavailable, EX_UNAVAILABLE);
  EXPECT_EQ(kExitNoPermission, EX_NOPERM);
  EXPECT_EQ(kExitConfig, EX_CONFIG);
}

TEST(ExitCodesTest, AreDistinct) {
  const std::set<int> codes = {kExitOk,          kExitFailure,      kExitUsage,  kExitDataError,
                               kExitNoInput,     kExitUnavailable,  kExitNoPermission,
                               kExitConfig,      kExitInterrupted};
  EXPECT_EQ(codes.size(), 9u);
}

}  // namespace
}  // namespace dcs::services
