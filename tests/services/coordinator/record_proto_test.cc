// Copyright 2026 The DCS Authors.
#include "services/coordinator/record_proto.h"

#include <string>
#include <vector>

#include "absl/time/time.h"
#include "gtest/gtest.h"
#include "services/pieces.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

// Bytes that differ from piece to piece, so a piece out of place shows.
std::string Bytes(size_t size) {
  std::string bytes(size, '\0');
  for (size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>(i * 7 / 3);
  return bytes;
}

TEST(RunProtoTest, FilesGoInPiecesInOrderAndAnEmptyFileIsOnePiece) {
  const std::vector<v1::RunFile> pieces = RunFilesToPieces(
      {{.path = "a", .contents = Bytes(kPieceBytes + 1)}, {.path = "b", .contents = ""}});
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].path(), "a");
  EXPECT_EQ(pieces[1].path(), "a");
  EXPECT_EQ(pieces[0].contents() + pieces[1].contents(), Bytes(kPieceBytes + 1));
  EXPECT_EQ(pieces[2].path(), "b");
  EXPECT_TRUE(pieces[2].contents().empty());
}

TEST(WorkerProtoTest, CarriesIdStateAndTimes) {
  const absl::Time registered = absl::FromUnixMillis(1'763'717'400'123);
  const absl::Time heartbeat = registered + absl::Milliseconds(4'567);
  coordinator::WorkerRecord record{
      .id = "learner-3",
      .info = {.role = WorkerRole::kLearner,
               .address = "10.1.2.3:50052",
               .libraries = {{"libtorch", "1.13.1"}, {"box2d", "2.4.1"}}},
      .state = coordinator::WorkerState::kLost,
      .registered_at = registered,
      .last_heartbeat_at = heartbeat};
  v1::Worker proto = WorkerToProto(record);
  EXPECT_EQ(proto.worker_id(), "learner-3");
  EXPECT_EQ(proto.state(), v1::WORKER_STATE_LOST);
  EXPECT_EQ(TimeFromProto(proto.registered_time()), registered);
  EXPECT_EQ(TimeFromProto(proto.last_heartbeat_time()), heartbeat);
  EXPECT_EQ(proto.info().role(), v1::WORKER_ROLE_LEARNER);
  EXPECT_EQ(proto.info().address(), "10.1.2.3:50052");
  EXPECT_EQ(proto.info().build().libraries_size(), 2);

  record.state = coordinator::WorkerState::kAlive;
  EXPECT_EQ(WorkerToProto(record).state(), v1::WORKER_STATE_ALIVE);
}

}  // namespace
}  // namespace dcs::services
