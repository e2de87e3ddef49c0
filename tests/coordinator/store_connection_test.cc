// Copyright 2026 The DCS Authors.
#include "coordinator/store_connection.h"

#include <SQLiteCpp/Exception.h>
#include <sqlite3.h>

#include "absl/status/status.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::coordinator::internal {
namespace {

using ::testing::HasSubstr;

absl::Status ErrorOf(int sqlite_code) {
  return StoreError("/data/coordinator.db", SQLite::Exception("what sqlite said", sqlite_code));
}

// Workers retry UNAVAILABLE with backoff and fail a run on anything else: a full disk must not
// end runs, a corrupt store must not be retried.
TEST(StoreErrorTest, AFullDiskIsRetryableAndNamesTheFile) {
  const absl::Status full = ErrorOf(SQLITE_FULL);
  EXPECT_EQ(full.code(), absl::StatusCode::kUnavailable);
  EXPECT_THAT(full.message(), HasSubstr("/data/coordinator.db: the disk is full"));
  EXPECT_THAT(full.message(), HasSubstr("what sqlite said"));
}

TEST(StoreErrorTest, ALockedStoreIsRetryable) {
  EXPECT_EQ(ErrorOf(SQLITE_BUSY).code(), absl::StatusCode::kUnavailable);
  EXPECT_EQ(ErrorOf(SQLITE_LOCKED).code(), absl::StatusCode::kUnavailable);
}

TEST(StoreErrorTest, ACorruptStoreIsDataLoss) {
  EXPECT_EQ(ErrorOf(SQLITE_CORRUPT).code(), absl::StatusCode::kDataLoss);
  EXPECT_EQ(ErrorOf(SQLITE_NOTADB).code(), absl::StatusCode::kDataLoss);
  EXPECT_THAT(ErrorOf(SQLITE_NOTADB).message(), HasSubstr("/data/coordinator.db is corrupt"));
}

TEST(StoreErrorTest, AnythingElseIsInternal) {
  EXPECT_EQ(ErrorOf(SQLITE_MISUSE).code(), absl::StatusCode::kInternal);
}

}  // namespace
}  // namespace dcs::coordinator::internal
