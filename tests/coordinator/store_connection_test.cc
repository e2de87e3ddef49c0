// Copyright 2026 The DCS Authors.
#include "coordinator/store_connection.h"

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>
#include <sqlite3.h>

#include <memory>
#include <string>
#include <utility>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "tests/testing/temp_dir.h"

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

class StoreConnectionTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    auto db = std::make_unique<SQLite::Database>(Path("store.db"),
                                                 SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    db->exec("PRAGMA journal_mode = WAL");
    db->exec("CREATE TABLE t (value INTEGER)");
    connection_ = std::make_unique<StoreConnection>(std::move(db), absl::Seconds(10));
  }

  // The `synchronous` setting a transaction of `commit` runs, and so commits, under: 2 is
  // FULL (synced), 1 NORMAL.
  int SynchronousOf(Commit commit) {
    const absl::StatusOr<int> setting = connection_->Transaction(
        [](SQLite::Database& db) -> absl::StatusOr<int> {
          return db.execAndGet("PRAGMA synchronous").getInt();
        },
        commit);
    EXPECT_TRUE(setting.ok()) << setting.status();
    return setting.value_or(-1);
  }

  std::unique_ptr<StoreConnection> connection_;
};

TEST_F(StoreConnectionTest, EachTransactionCommitsAsItAsks) {
  EXPECT_EQ(SynchronousOf(Commit::kSynced), 2);
  EXPECT_EQ(SynchronousOf(Commit::kUnsynced), 1);
  EXPECT_EQ(SynchronousOf(Commit::kUnsynced), 1);
  // A synced commit after unsynced ones is synced again.
  EXPECT_EQ(SynchronousOf(Commit::kSynced), 2);
}

TEST_F(StoreConnectionTest, AnUnsyncedCommitIsCommitted) {
  ASSERT_TRUE(connection_
                  ->Transaction(
                      [](SQLite::Database& db) -> absl::Status {
                        db.exec("INSERT INTO t VALUES (7)");
                        return absl::OkStatus();
                      },
                      Commit::kUnsynced)
                  .ok());
  // Another connection, as a coordinator restarted after a crash of its own opens the file.
  SQLite::Database reader(Path("store.db"), SQLite::OPEN_READONLY);
  EXPECT_EQ(reader.execAndGet("SELECT value FROM t").getInt(), 7);
}

}  // namespace
}  // namespace dcs::coordinator::internal
