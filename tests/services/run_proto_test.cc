// Copyright 2026 The DCS Authors.
#include "services/run_proto.h"

#include <string>
#include <vector>

#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

// Bytes that differ from piece to piece, so a piece out of place shows.
std::string Bytes(size_t size) {
  std::string bytes(size, '\0');
  for (size_t i = 0; i < size; ++i) bytes[i] = static_cast<char>(i * 7 / 3);
  return bytes;
}

TEST(RunProtoTest, OnlyCompletedFailedAndCancelledRunsAndSweepsHaveEnded) {
  EXPECT_FALSE(RunEnded(v1::RUN_STATE_QUEUED));
  EXPECT_FALSE(RunEnded(v1::RUN_STATE_RUNNING));
  EXPECT_TRUE(RunEnded(v1::RUN_STATE_COMPLETED));
  EXPECT_TRUE(RunEnded(v1::RUN_STATE_FAILED));
  EXPECT_TRUE(RunEnded(v1::RUN_STATE_CANCELLED));
  EXPECT_FALSE(SweepEnded(v1::SWEEP_STATE_QUEUED));
  EXPECT_FALSE(SweepEnded(v1::SWEEP_STATE_RUNNING));
  EXPECT_TRUE(SweepEnded(v1::SWEEP_STATE_COMPLETED));
  EXPECT_TRUE(SweepEnded(v1::SWEEP_STATE_FAILED));
  EXPECT_TRUE(SweepEnded(v1::SWEEP_STATE_CANCELLED));
}

TEST(RunProtoTest, ACheckpointLargerThanAPieceGoesInPiecesAndComesBackWhole) {
  const run::PackedCheckpoint checkpoint{.name = "000000000256",
                                         .learner = Bytes(2 * kPieceBytes + 5),
                                         .run_state = Bytes(100),
                                         .learner_sha256 = "aa",
                                         .run_state_sha256 = "bb"};
  const std::vector<v1::CheckpointPiece> pieces = CheckpointToPieces(checkpoint);
  ASSERT_EQ(pieces.size(), 3u);
  for (const v1::CheckpointPiece& piece : pieces) EXPECT_LE(piece.ByteSizeLong(), 2 * kPieceBytes);
  EXPECT_TRUE(pieces[1].name().empty());
  run::PackedCheckpoint back;
  for (size_t i = 0; i < pieces.size(); ++i) {
    ASSERT_TRUE(AddCheckpointPiece(pieces[i], i == 0, back).ok());
  }
  EXPECT_EQ(back.name, checkpoint.name);
  EXPECT_EQ(back.learner, checkpoint.learner);
  EXPECT_EQ(back.run_state, checkpoint.run_state);
  EXPECT_EQ(back.learner_sha256, "aa");
  EXPECT_EQ(back.run_state_sha256, "bb");
}

TEST(RunProtoTest, AStreamedCheckpointMustNameItselfFirstAndOnlyItself) {
  run::PackedCheckpoint into;
  v1::CheckpointPiece unnamed;
  unnamed.set_learner("x");
  EXPECT_THAT(AddCheckpointPiece(unnamed, /*first=*/true, into).message(),
              HasSubstr("names no checkpoint"));
  v1::CheckpointPiece first;
  first.set_name("000000000256");
  ASSERT_TRUE(AddCheckpointPiece(first, /*first=*/true, into).ok());
  v1::CheckpointPiece other;
  other.set_name("000000000512");
  EXPECT_EQ(AddCheckpointPiece(other, /*first=*/false, into).code(),
            absl::StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace dcs::services
