// Copyright 2026 The DCS Authors.
//
// A payload cut into a stream's messages comes back whole, with the header; what is too large
// or does not parse is refused, naming the payload.

#include "services/pieces.h"

#include <string>
#include <vector>

#include "dcs/v1/learner_service.pb.h"
#include "dcs/v1/trajectory.pb.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"

namespace dcs::services {
namespace {

using ::testing::HasSubstr;

TEST(PiecesTest, SplitsIntoPiecesOfAtMostTheLimit) {
  const std::string bytes(2 * kPieceBytes + 3, 'x');
  const std::vector<absl::string_view> pieces = SplitIntoPieces(bytes);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].size(), kPieceBytes);
  EXPECT_EQ(pieces[2].size(), 3u);
  EXPECT_EQ(SplitIntoPieces("").size(), 1u);  // an empty payload still makes one message
}

TEST(PiecesTest, AHeaderAndAPayloadComeBackWhole) {
  v1::PushRolloutRequest header;
  header.mutable_lease()->set_run_id("run-7");
  header.set_rollout(4);
  std::string payload(kPieceBytes + 10, '\0');
  for (size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<char>(i * 31);
  std::vector<v1::PushRolloutRequest> messages =
      CutIntoMessages(header, payload, &v1::PushRolloutRequest::mutable_data);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[1].rollout(), 0);  // the header travels once
  for (const v1::PushRolloutRequest& message : messages) {
    EXPECT_LE(message.ByteSizeLong(), kPieceBytes + 100);
  }
  PieceJoiner<v1::PushRolloutRequest> joiner(&v1::PushRolloutRequest::mutable_data, "a rollout");
  EXPECT_FALSE(joiner.started());
  for (v1::PushRolloutRequest& message : messages) {
    ASSERT_TRUE(joiner.Add(std::move(message)).ok());
  }
  EXPECT_TRUE(joiner.started());
  EXPECT_EQ(joiner.header().lease().run_id(), "run-7");
  EXPECT_EQ(joiner.header().rollout(), 4);
  EXPECT_TRUE(joiner.header().data().empty());
  EXPECT_EQ(joiner.payload(), payload);
}

TEST(PiecesTest, RefusesTooMuchAndWhatDoesNotParseNamingIt) {
  PieceJoiner<v1::PushRolloutRequest> small(&v1::PushRolloutRequest::mutable_data, "a rollout",
                                           /*max_bytes=*/10);
  v1::PushRolloutRequest piece;
  piece.set_data("123456");
  ASSERT_TRUE(small.Add(piece).ok());
  const absl::Status too_much = small.Add(piece);
  EXPECT_EQ(too_much.code(), absl::StatusCode::kResourceExhausted);
  EXPECT_EQ(too_much.message(), "a rollout is larger than 10 bytes");

  v1::SlotRollout rollout;
  const absl::Status garbage = small.Parse(rollout);  // "123456" is not a SlotRollout
  EXPECT_EQ(garbage.code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(garbage.message(), HasSubstr("a rollout (6 bytes in pieces) does not parse"));
}

}  // namespace
}  // namespace dcs::services
